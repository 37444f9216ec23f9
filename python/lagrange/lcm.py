"""LCM for Python without python3-lcm (which Debian 12 lacks): a thin ctypes
layer over LCM's own C library, liblcm.so.1 (Debian package liblcm1).

The library does all the wire work -- fragments, every LCM URL (udpm://,
file://, memq://) -- and nothing of the transport is written here. Only what
a process of a run needs: create, publish, subscribe, handle with a timeout,
the file descriptor to select on.

    import lagrange.lcm
    lc = lagrange.lcm.LCM("udpm://239.255.76.67:7667?ttl=0")
    lc.subscribe("PLANT_POSITION", lambda channel, data: print(channel, len(data)))
    lc.publish("CHANNEL", b"bytes")
    lc.handle_timeout(100)   # > 0: a message was handled; 0: timed out

Set LAGRANGE_LIBLCM to the library's path to use another build of it.
"""

import ctypes
import errno
import os


class LCMError(RuntimeError):
    """LCM could not do what was asked (no library, a bad URL, a failed publish)."""


_LIBRARY_NAME = "liblcm.so.1"


class _RecvBuf(ctypes.Structure):
    # lcm_recv_buf_t (lcm/lcm.h): data, data_size, recv_utime, lcm
    _fields_ = [
        ("data", ctypes.c_void_p),
        ("data_size", ctypes.c_uint32),
        ("recv_utime", ctypes.c_int64),
        ("lcm", ctypes.c_void_p),
    ]


_HANDLER = ctypes.CFUNCTYPE(None, ctypes.POINTER(_RecvBuf), ctypes.c_char_p, ctypes.c_void_p)
_lib = None


def library():
    """LCM's C library, loaded once. Raises LCMError naming the package when
    it is absent."""
    global _lib
    if _lib is not None:
        return _lib
    path = os.environ.get("LAGRANGE_LIBLCM", _LIBRARY_NAME)
    try:
        lib = ctypes.CDLL(path, use_errno=True)  # errno tells a signal (EINTR) from a failure
    except OSError as e:
        raise LCMError(
            "lagrange.lcm needs LCM's C library %s, which could not be loaded (%s); install the Debian "
            "package liblcm1 (apt-get install liblcm1), or set LAGRANGE_LIBLCM to its path" % (path, e)
        ) from None
    lib.lcm_create.restype = ctypes.c_void_p
    lib.lcm_create.argtypes = [ctypes.c_char_p]
    lib.lcm_destroy.restype = None
    lib.lcm_destroy.argtypes = [ctypes.c_void_p]
    lib.lcm_publish.restype = ctypes.c_int
    lib.lcm_publish.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_void_p, ctypes.c_uint]
    lib.lcm_subscribe.restype = ctypes.c_void_p
    lib.lcm_subscribe.argtypes = [ctypes.c_void_p, ctypes.c_char_p, _HANDLER, ctypes.c_void_p]
    lib.lcm_unsubscribe.restype = ctypes.c_int
    lib.lcm_unsubscribe.argtypes = [ctypes.c_void_p, ctypes.c_void_p]
    lib.lcm_handle_timeout.restype = ctypes.c_int
    lib.lcm_handle_timeout.argtypes = [ctypes.c_void_p, ctypes.c_int]
    lib.lcm_get_fileno.restype = ctypes.c_int
    lib.lcm_get_fileno.argtypes = [ctypes.c_void_p]
    _lib = lib
    return lib


class Subscription:
    """What LCM.subscribe returns: pass it to LCM.unsubscribe."""

    def __init__(self, handle, callback):
        self.handle = handle
        self.callback = callback  # the C callback; kept alive as long as the subscription


class LCM:
    """One LCM instance on `url` ("" or None: LCM_DEFAULT_URL or LCM's default)."""

    def __init__(self, url=None):
        self._lib = library()
        self._lcm = self._lib.lcm_create(url.encode() if url else None)
        if not self._lcm:
            raise LCMError("LCM could not be created on %r; expected a URL such as udpm://239.255.76.67:7667?ttl=0, "
                           "file:///path/to/log?mode=r or memq://" % (url or "the default URL"))
        self._subscriptions = []
        self._error = None
        # LCM's receive time [us, wall clock] of the message being handled
        # (lcm_recv_buf_t.recv_utime), for a handler that times its input.
        self.recv_utime = 0

    def close(self):
        if self._lcm:
            self._lib.lcm_destroy(self._lcm)
            self._lcm = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    def _check_open(self):
        if not self._lcm:
            raise LCMError("this LCM instance is closed")

    def publish(self, channel, data):
        """Publishes bytes on a channel."""
        self._check_open()
        data = bytes(data)
        if self._lib.lcm_publish(self._lcm, channel.encode(), data, len(data)) != 0:
            raise LCMError("LCM could not publish %d bytes on %s" % (len(data), channel))

    def subscribe(self, channel, handler):
        """Calls handler(channel, data: bytes) for each message on `channel`
        (a regular expression, as in LCM) while handle/handle_timeout runs.
        An exception in the handler is raised from the handle call."""
        self._check_open()

        def call(rbuf, channel_name, _user):
            if self._error is not None:
                return
            try:
                buf = rbuf.contents
                data = ctypes.string_at(buf.data, buf.data_size) if buf.data_size else b""
                self.recv_utime = buf.recv_utime
                handler(channel_name.decode("utf-8", "replace"), data)
            except BaseException as e:  # not across the C frames: raised after them
                self._error = e

        callback = _HANDLER(call)
        handle = self._lib.lcm_subscribe(self._lcm, channel.encode(), callback, None)
        if not handle:
            raise LCMError("LCM could not subscribe to %s" % channel)
        sub = Subscription(handle, callback)
        self._subscriptions.append(sub)
        return sub

    def unsubscribe(self, sub):
        self._check_open()
        if self._lib.lcm_unsubscribe(self._lcm, sub.handle) != 0:
            raise LCMError("LCM could not unsubscribe")
        self._subscriptions.remove(sub)

    def handle_timeout(self, timeout_ms):
        """Waits up to timeout_ms for a message and dispatches it: > 0 when one
        was handled, 0 on timeout."""
        self._check_open()
        status = self._lib.lcm_handle_timeout(self._lcm, int(timeout_ms))
        if self._error is not None:
            error, self._error = self._error, None
            raise error
        if status < 0:
            # A signal in the wait (SIGCONT when the launcher restarts a peer,
            # SIGTERM whose handler sets a flag) is no failure: nothing was handled.
            if ctypes.get_errno() == errno.EINTR:
                return 0
            raise LCMError("LCM failed while waiting for a message")
        return status

    def fileno(self):
        """The file descriptor that becomes readable when a message is waiting."""
        self._check_open()
        return self._lib.lcm_get_fileno(self._lcm)
