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
import struct
import time

MAC_BYTES = 32
FNV_OFFSET_BASIS = 1469598103934665603
FNV_PRIME = 1099511628211
_MASK64 = (1 << 64) - 1


def fnv1a(data, basis=FNV_OFFSET_BASIS, _prime=FNV_PRIME, _mask=_MASK64):
    """FNV-1a (64 bit) of bytes, as an unsigned integer."""
    # Four bytes a turn, masked once: the product's low 64 bits depend only on
    # the factors' low 64 bits, so masking later gives the same hash; a third
    # less time than a byte a turn (every message a plant sends or takes is
    # hashed: this is most of a Python helper's cost per period).
    h = basis
    it = iter(data)
    for b0, b1, b2, b3 in zip(it, it, it, it):
        h = ((((((h ^ b0) * _prime ^ b1) * _prime) ^ b2) * _prime ^ b3) * _prime) & _mask
    for b in data[len(data) & ~3:]:
        h = ((h ^ b) * _prime) & _mask
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


_CHECKSUM = struct.Struct(">q")


def sealed_encoding(msg):
    """seal(msg).encode() with one encoding instead of two: the message
    encoded with checksum 0, hashed, and the checksum written into its
    8 bytes. For a message whose first field is its header (every message
    with a header: the checksum follows the fingerprint, tick, sim_time,
    publish_utime, run_id, the publisher's length, text and NUL, pid, seq)."""
    msg.header.checksum = 0
    data = msg.encode()
    # The publisher's length, NUL included, is the uint32 at offset 40.
    at = 56 + int.from_bytes(data[40:44], "big")
    value = _signed64(fnv1a(data) | 1)
    msg.header.checksum = value
    return data[:at] + _CHECKSUM.pack(value) + data[at + 8:]


def intact(msg, encoding=None):
    """Whether the checksum `msg` carries is the one its fields give.
    `encoding`: the bytes `msg` was decoded from, exactly (no trailing
    bytes), when known: then those are hashed, with the checksum's 8 bytes
    zeroed, instead of encoding `msg` again -- the same answer for every
    message encoded as LCM encodes (a keyed sender's non-canonical bytes, a
    boolean other than 0 or 1, are hashed as sent); a mismatch is checked
    again the slow way, so nothing the old check took is refused."""
    if encoding is not None and len(encoding) >= 44:
        at = 56 + int.from_bytes(encoding[40:44], "big")
        if len(encoding) >= at + 8 and _signed64(fnv1a(encoding[:at] + bytes(8) + encoding[at + 8:]) | 1) \
                == msg.header.checksum:
            return True
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
