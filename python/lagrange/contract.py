"""The wire contract every process of a run keeps (docs/external_programs.md).

Every datagram is a message's LCM encoding followed by a 32-byte MAC:
HMAC-SHA256 of the encoding under the run's key. Every message's header
carries the run's id, its publisher, a per-channel sequence number and a
checksum: FNV-1a (64 bit) of the message encoded with checksum 0, lowest bit
set. The FNV offset basis is lagrange's 1469598103934665603, not the
standard 14695981039346656037: a digit was lost when the project first wrote
it, and every log carries checksums made that way.
"""

import hashlib
import hmac
import os
import time

MAC_BYTES = 32
FNV_OFFSET_BASIS = 1469598103934665603
FNV_PRIME = 1099511628211
_MASK64 = (1 << 64) - 1


def fnv1a(data, basis=FNV_OFFSET_BASIS):
    """FNV-1a (64 bit) of bytes, as an unsigned integer."""
    h = basis
    for b in data:
        h = ((h ^ b) * FNV_PRIME) & _MASK64
    return h


def _signed64(value):
    return value - (1 << 64) if value >= (1 << 63) else value


def checksum(msg):
    """The checksum `msg` should carry: FNV-1a of its encoding with checksum 0,
    lowest bit set, as LCM's int64 (signed). `msg.header.checksum` is left as
    it was."""
    kept = msg.header.checksum
    msg.header.checksum = 0
    try:
        return _signed64(fnv1a(msg.encode()) | 1)
    finally:
        msg.header.checksum = kept


def seal(msg):
    """Sets `msg.header.checksum` last, after every other field."""
    msg.header.checksum = checksum(msg)
    return msg


def intact(msg):
    """Whether the checksum `msg` carries is the one its fields give."""
    return msg.header.checksum == checksum(msg)


class Key:
    """A run's secret key: 32 bytes, read from its key file (64 hex digits)."""

    def __init__(self, key_bytes):
        if len(key_bytes) != 32:
            raise ValueError("a run's key is 32 bytes; got %d" % len(key_bytes))
        self._key = bytes(key_bytes)

    @classmethod
    def from_file(cls, path):
        """Reads a key file written by `lagrange run` or `lagrange keygen`."""
        try:
            with open(path, "r", encoding="ascii") as f:
                text = f.read(200).strip()
        except (OSError, UnicodeDecodeError) as e:
            raise ValueError("cannot read the run's key file %s (%s); expected 64 hex digits" % (path, e)) from None
        try:
            key = bytes.fromhex(text)
        except ValueError:
            key = b""
        if len(key) != 32:
            raise ValueError("the run's key file %s does not hold 64 hex digits" % path)
        return cls(key)

    def sign(self, encoding):
        """The datagram to publish: the encoding and its MAC."""
        return encoding + hmac.new(self._key, encoding, hashlib.sha256).digest()

    def authenticate(self, datagram):
        """The encoding inside a datagram whose MAC is valid (checked in
        constant time), or None: nothing else should be decoded."""
        if len(datagram) < MAC_BYTES:
            return None
        payload, tag = datagram[:-MAC_BYTES], datagram[-MAC_BYTES:]
        good = hmac.new(self._key, payload, hashlib.sha256).digest()
        return payload if hmac.compare_digest(good, tag) else None


def clock_offset_us(environ=None):
    """Wall minus monotonic [µs]: LAGRANGE_CLOCK_OFFSET_US, or measured now."""
    text = (os.environ if environ is None else environ).get("LAGRANGE_CLOCK_OFFSET_US", "")
    try:
        return int(text)
    except ValueError:
        return time.time_ns() // 1000 - time.monotonic_ns() // 1000


class Headers:
    """The headers a process stamps: its run, its name, its pid and one
    sequence number per channel (1 for the first message, re-sent ones
    included)."""

    def __init__(self, run_id, publisher):
        self.run_id = run_id
        self.publisher = publisher
        self.pid = os.getpid()
        self._seq = {}
        # publish_utime: the run's clock (transport/run_clock.hpp): the
        # monotonic clock moved onto the wall clock by the offset the launcher
        # hands every process of the run (LAGRANGE_CLOCK_OFFSET_US), so that a
        # latency between two processes is never negative; else our own.
        self._offset = clock_offset_us()

    def utime(self):
        return time.monotonic_ns() // 1000 + self._offset

    def stamp(self, header, channel, tick, sim_time):
        """Fills `header` for the next message on `channel` (checksum 0: seal last)."""
        self._seq[channel] = self._seq.get(channel, 0) + 1
        header.tick = max(0, int(tick))
        header.sim_time = float(sim_time)
        header.publish_utime = self.utime()
        header.run_id = self.run_id
        header.publisher = self.publisher
        header.publisher_pid = self.pid
        header.seq = self._seq[channel]
        header.checksum = 0
        return header
