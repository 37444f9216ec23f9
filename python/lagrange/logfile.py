"""A reader of LCM log files with the bounds checks of the C++ one
(logs/log_event_reader.hpp). The format, every field big-endian:

    sync word 0xEDA1DA01 | event number int64 | timestamp int64 |
    channel length int32 | data length int32 | channel | data

Both lengths are checked against a sane limit and against the bytes left in
the file before anything is read into memory. What stands where an event
should start:

- a whole event: yielded;
- a header whose lengths no LCM log can hold (negative, a channel name longer
  than 999 bytes, data larger than LCM's largest message): LogError names the
  file, the byte offset and what was expected;
- no sync word (a corrupt stretch): skipped up to the next sync word that
  starts a whole, sane event, and counted (scan.skipped_bytes);
- an event running past the end of the file (a logger killed while writing):
  the end; the rest is counted (scan.unreadable_tail_bytes);
- a whole event larger than its channel's messages can be in this log
  (`bounds`, lagrange/log_bounds.py): skipped without reading its data, and
  named (scan.oversized_events, scan.first_oversized).

The file is opened without blocking and refused unless it is a regular file:
a FIFO, /dev/zero or a directory is named and refused before a byte is read,
and so is a file of /proc or /sys (the kernel makes it up as it is read:
/proc/kcore claims 128 TB). `read_regular_file` reads the other files of a
run (summary.json, the resolved scenario) the same way, whole but at most a
given size, as the C++ readers do (config/input_file.hpp, util/input_file.hpp).
"""

import os
import stat
import struct

from . import log_bounds

SYNC_WORD = 0xEDA1DA01
HEADER_BYTES = 4 + 8 + 8 + 4 + 4
MAX_CHANNEL_BYTES = 999
MAX_DATA_BYTES = 1 << 28  # LCM_MAX_MESSAGE_SIZE
_SYNC = struct.pack(">I", SYNC_WORD)
_HEADER = struct.Struct(">Iqqii")


class LogError(ValueError):
    """A file that is not an LCM log, is malformed, or cannot be read."""


class Event:
    __slots__ = ("eventnum", "timestamp", "channel", "data", "offset")

    def __init__(self, eventnum, timestamp, channel, data, offset):
        self.eventnum = eventnum
        self.timestamp = timestamp  # µs, the logger's receive time
        self.channel = channel
        self.data = data
        self.offset = offset  # the event's byte offset in the file


# Oversized events named in the warning; the rest are counted.
_OVERSIZED_NAMED = 3
_PER_TICK = ("PLANT_POSITION", "PLANT_TRUTH", "PLANT_MOTOR", "PLANT_RATE", "CONTROL_COMMAND", "ACTUATOR_STATE")


class Scan:
    """What a pass over a log read."""

    def __init__(self):
        self.events = 0
        self.skipped_bytes = 0
        self.first_skipped_at = -1
        self.unreadable_tail_bytes = 0
        self.channels = {}
        self.oversized_events = 0  # whole events skipped unread: over their channel's bound
        self.oversized_bytes = 0
        self.first_oversized = []  # (channel, offset, data bytes, bound, tick or None), the first few
        self.bounds_origin = ""

    def problems(self):
        """Warnings for a person; empty when the log was read whole."""
        out = []
        if self.skipped_bytes:
            out.append("%d corrupt bytes between events were skipped (the first stretch starts at byte %d, "
                       "where an event with the LCM sync word 0xEDA1DA01 was expected)"
                       % (self.skipped_bytes, self.first_skipped_at))
        if self.unreadable_tail_bytes:
            out.append("the log ends with %d bytes that are not a whole event (cut short, e.g. a run killed "
                       "while writing); %d whole events before them were read"
                       % (self.unreadable_tail_bytes, self.events))
        if self.oversized_events:
            named = "; ".join(
                "%s at byte %d%s: %d bytes, at most %d expected"
                % (channel, offset, "" if tick is None else " (tick %d)" % tick, size, bound)
                for channel, offset, size, bound, tick in self.first_oversized)
            more = "; ..." if self.oversized_events > len(self.first_oversized) else ""
            out.append("%d %s larger than its channel's messages can be and skipped unread, never decoded "
                       "(%s%s); the bound is the message with the counts of %s"
                       % (self.oversized_events, "event was" if self.oversized_events == 1 else "events were",
                          named, more, self.bounds_origin))
        return out


_EVENT, _NO_SYNC, _CUT_SHORT, _MALFORMED = range(4)


def _kind(mode):
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


# Where the kernel makes files up as they are read: "regular" files whose
# size says nothing (0 bytes, or /proc/kcore's 128 TB) and whose reads may wait.
_PSEUDO_FILESYSTEMS = ("/proc", "/sys")


def _pseudo_filesystem(device):
    for root in _PSEUDO_FILESYSTEMS:
        try:
            if os.stat(root).st_dev == device:
                return root
        except OSError:
            pass
    return None


def open_regular(path, expected):
    """A descriptor of `path`, opened without blocking (a FIFO without a
    writer does not wait) and looked at through itself (fstat: what is
    checked is what will be read, a symbolic link followed), and its
    os.stat_result. Raises LogError naming the file, what it is and
    `expected` unless it is a regular file outside /proc and /sys. The
    descriptor stays non-blocking; it is the caller's to close."""
    path = str(path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
    except OSError as e:
        raise LogError("cannot read '%s' (%s); expected %s" % (path, e.strerror, expected)) from None
    try:
        st = os.fstat(fd)
        if not stat.S_ISREG(st.st_mode):
            raise LogError("'%s' is %s; expected %s (a regular file)" % (path, _kind(st.st_mode), expected))
        root = _pseudo_filesystem(st.st_dev)
        if root is not None:
            raise LogError("'%s' is a file of %s (made up by the kernel as it is read); expected %s (a regular "
                           "file)" % (path, root, expected))
    except BaseException:
        os.close(fd)
        raise
    return fd, st


def size_text(size):
    """"1 MiB", "16 MiB", "2.5 MiB", "800 bytes" (config::sizeText)."""
    if size < 1024:
        return "%d bytes" % size
    if size >= 1 << 20:
        return "%.3g MiB" % (size / float(1 << 20))
    return "%.3g KiB" % (size / 1024.0)


def read_regular_file(path, max_bytes, expected):
    """The bytes of `path` when it is a regular file (open_regular) of at
    most `max_bytes`; read without ever waiting and never more than
    max_bytes + 1 bytes (a file that grows while it is read is caught, not
    read whole). Raises LogError naming the file, what was wrong and
    `expected`."""
    path = str(path)
    fd, st = open_regular(path, expected)
    try:
        if st.st_size > max_bytes:
            raise LogError("'%s' is %s; expected %s of at most %s"
                           % (path, size_text(st.st_size), expected, size_text(max_bytes)))
        chunks, got = [], 0
        while got <= max_bytes:
            try:
                chunk = os.read(fd, min(1 << 20, max_bytes + 1 - got))
            except BlockingIOError:
                raise LogError("'%s' cannot be read without waiting; expected %s (a regular file)"
                               % (path, expected)) from None
            except InterruptedError:
                continue
            except OSError as e:
                raise LogError("cannot read '%s' (%s); expected %s" % (path, e.strerror, expected)) from None
            if not chunk:
                break
            chunks.append(chunk)
            got += len(chunk)
        if got > max_bytes:
            raise LogError("'%s' is larger than %s (it grew while it was read); expected %s of at most %s"
                           % (path, size_text(max_bytes), expected, size_text(max_bytes)))
        return b"".join(chunks)
    finally:
        os.close(fd)


class LogReader:
    """Reads a log's events in file order: `for event in LogReader(path)`.
    `scan` holds what was read once the iteration ends. `bounds`
    (log_bounds.Bounds; default: the project's limits) bounds each channel's
    events; `only_channel` hands out only that channel's events, passing the
    others over unread."""

    def __init__(self, path, bounds=None, only_channel=None):
        self.path = str(path)
        # Without blocking (a FIFO), then looked at through the descriptor that will be read.
        fd, _ = open_regular(self.path, "an LCM log file")
        os.set_blocking(fd, True)
        self._file = os.fdopen(fd, "rb")
        self._size = os.fstat(self._file.fileno()).st_size
        self.bounds = bounds if bounds is not None else log_bounds.project_limits()
        self.only_channel = only_channel
        self.scan = Scan()
        self.scan.bounds_origin = self.bounds.origin

    def close(self):
        self._file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _skip_oversized(self, offset, channel, channel_bytes, data_bytes, bound):
        self.scan.oversized_events += 1
        self.scan.oversized_bytes += HEADER_BYTES + channel_bytes + data_bytes
        if len(self.scan.first_oversized) >= _OVERSIZED_NAMED:
            return
        tick = None  # the tick its header claims: after the 8-byte fingerprint
        if channel in _PER_TICK and data_bytes >= 16:
            tick = struct.unpack(">q", self._read_at(offset + HEADER_BYTES + channel_bytes + 8, 8))[0]
        self.scan.first_oversized.append((channel, offset, data_bytes, bound, tick))

    def _read_at(self, offset, n):
        self._file.seek(offset)
        return self._file.read(n)

    def _inspect(self, offset):
        left = self._size - offset
        head = self._read_at(offset, HEADER_BYTES)
        if len(head) < 4:
            return _CUT_SHORT, None, None
        if head[:4] != _SYNC:
            return _NO_SYNC, None, None
        if len(head) < HEADER_BYTES:
            return _CUT_SHORT, None, None
        _, eventnum, timestamp, channel_bytes, data_bytes = _HEADER.unpack(head)
        at = "%s: malformed LCM log: the event at byte %d" % (self.path, offset)
        if channel_bytes < 1 or channel_bytes > MAX_CHANNEL_BYTES:
            return _MALFORMED, None, "%s gives a channel name length of %d bytes; expected 1 to %d" % (
                at, channel_bytes, MAX_CHANNEL_BYTES)
        if data_bytes < 0 or data_bytes > MAX_DATA_BYTES:
            return _MALFORMED, None, (
                "%s gives a data length of %d bytes; expected 0 to %d (LCM's largest message), and at most "
                "the %d bytes left in the file after its header and channel"
                % (at, data_bytes, MAX_DATA_BYTES, max(0, left - HEADER_BYTES - channel_bytes)))
        if HEADER_BYTES + channel_bytes + data_bytes > left:
            return _CUT_SHORT, None, None
        return _EVENT, (eventnum, timestamp, channel_bytes, data_bytes), None

    def _next_event_start(self, start):
        candidate = start
        while candidate + 4 <= self._size:
            self._file.seek(candidate)
            found = -1
            position = candidate
            while position < self._size:
                chunk = self._file.read(1 << 16)
                if not chunk:
                    break
                i = chunk.find(_SYNC)
                if i >= 0:
                    found = position + i
                    break
                # keep 3 bytes: a sync word across two chunks
                position += max(1, len(chunk) - 3)
                self._file.seek(position)
            if found < 0:
                return -1
            kind, _, _ = self._inspect(found)
            if kind == _EVENT:
                return found
            candidate = found + 1
        return -1

    def __iter__(self):
        position = 0
        while position < self._size:
            kind, header, problem = self._inspect(position)
            if kind == _MALFORMED:
                raise LogError(problem)
            if kind != _EVENT:
                following = self._next_event_start(position + 1)
                if following < 0:
                    self.scan.unreadable_tail_bytes = self._size - position
                    break
                if self.scan.first_skipped_at < 0:
                    self.scan.first_skipped_at = position
                self.scan.skipped_bytes += following - position
                position = following
                continue
            eventnum, timestamp, channel_bytes, data_bytes = header
            channel = self._read_at(position + HEADER_BYTES, channel_bytes).decode("utf-8", "replace")
            start, position = position, position + HEADER_BYTES + channel_bytes + data_bytes
            if self.only_channel is not None and channel != self.only_channel:
                self.scan.events += 1
                self.scan.channels[channel] = self.scan.channels.get(channel, 0) + 1
                continue
            bound = self.bounds.largest_data(channel)
            if bound is not None and data_bytes > bound:  # not one of the run's messages: never read
                self._skip_oversized(start, channel, channel_bytes, data_bytes, bound)
                continue
            data = self._read_at(start + HEADER_BYTES + channel_bytes, data_bytes)
            self.scan.events += 1
            self.scan.channels[channel] = self.scan.channels.get(channel, 0) + 1
            yield Event(eventnum, timestamp, channel, data, start)
        if self.scan.events == 0 and self.scan.oversized_events == 0 and self._size > 0:
            raise LogError("%s is not an LCM log: no event in its %d bytes (expected events starting with the LCM "
                           "sync word 0xEDA1DA01)" % (self.path, self._size))
