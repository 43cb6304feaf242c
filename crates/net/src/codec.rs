//! Byte-level building blocks shared by the replay file and the wire messages.
//!
//! # Why postcard, and our own framing
//!
//! Structured values with many fields (the replay header, which embeds the match
//! [`Settings`](craterfield_sim::Settings)) are serialized with **postcard 1.x**: its wire format
//! is documented and declared stable since 1.0 (a file written today decodes with any
//! later 1.x), compact (integers are LEB128 varints, signed ones zigzagged), maintained,
//! and `no_std`-capable. The alternatives were ruled out:
//!
//! - bincode: 3.0.0 on crates.io is a `compile_error!` placeholder and RUSTSEC-2025-0141
//!   marks the crate unmaintained (2.0.1 still works, but nothing will be fixed);
//! - bitcode: no stable format across versions, so old replays would stop decoding;
//! - wincode: too young to bet a file format on.
//!
//! Postcard is only used *inside* sections. The container around them (magic, format
//! version, section lengths, CRC-32) is our own, written with the helpers here and
//! documented byte by byte in [`super::replay`] and [`super::wire`], so the layout does
//! not depend on any crate and the version field lets it change later. The bulk data (the
//! per-tick inputs, the hashes, the events) is also hand-coded: a generic serializer cannot
//! exploit run lengths, deltas and per-message quanta, which is where the size goes.
//!
//! # Integers
//!
//! - fixed-width integers are little-endian (`u16 LE`, `u32 LE`, `u64 LE`);
//! - `varint` is unsigned LEB128: seven bits per byte, least significant group first, the
//!   high bit set on every byte but the last; at most 10 bytes for a `u64`, and the
//!   shortest form is required (a final `0x00` byte after a continuation is rejected);
//! - `zigzag` maps a signed value to a varint: `0, -1, 1, -2, ...` become `0, 1, 2, 3, ...`.
//!
//! # Hostile input
//!
//! Every read is bounds-checked and returns a [`DecodeError`] naming the section and the
//! byte offset. Counts are checked against [`DecodeLimits`] and against the bytes that
//! remain (every element takes at least one byte) before anything is allocated, so a
//! short input can never make a decoder reserve much memory.

use std::borrow::Cow;

use super::error::{DecodeError, DecodeErrorKind};

/// CRC-32 (IEEE 802.3, the polynomial of zlib and PNG) of `bytes`, as stored at the end of
/// every file and message.
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

/// Bounds a decoder enforces before allocating anything.
///
/// The defaults accept every file a real match produces; a server taking files from
/// strangers may lower them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DecodeLimits {
    /// Longest accepted input, bytes (default 256 MiB).
    pub max_bytes: usize,
    /// Most ticks in a replay (default 4 hours at 60 Hz: 864,000). Runs of identical rows
    /// are compact, so a short file may still decode to `max_ticks * max_players` inputs
    /// of 6 bytes (about 41 MB with the defaults); this limit is what bounds it.
    pub max_ticks: u32,
    /// Most players in a replay (default [`MAX_PLAYERS`](craterfield_sim::MAX_PLAYERS); the
    /// format holds at most 8).
    pub max_players: u8,
    /// Most events in a terrain snapshot (default 65,536: a joiner replays each, a few
    /// seconds at worst; a longer history is sent as a world state, see
    /// [`crate::state`]).
    pub max_events: u32,
    /// Most events in one event batch (default 4,096: at most a few tenths of a second of
    /// a receiver's time, where a 2^20-event batch cost 46 s).
    pub max_batch_events: u32,
    /// Longest world-state message, bytes (default 32 MiB; decoding one allocates at most
    /// a few times its length).
    pub max_state_bytes: usize,
}

impl Default for DecodeLimits {
    fn default() -> Self {
        DecodeLimits {
            max_bytes: 256 << 20,
            max_ticks: 60 * 60 * 60 * 4,
            max_players: craterfield_sim::MAX_PLAYERS as u8,
            max_events: 1 << 16,
            max_batch_events: 4096,
            max_state_bytes: 32 << 20,
        }
    }
}

/// Appends little-endian integers and varints to a byte vector.
#[derive(Default)]
pub(crate) struct Writer {
    pub(crate) buf: Vec<u8>,
}

impl Writer {
    pub(crate) fn u8(&mut self, v: u8) {
        self.buf.push(v);
    }

    pub(crate) fn u16(&mut self, v: u16) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    pub(crate) fn u32(&mut self, v: u32) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    pub(crate) fn u64(&mut self, v: u64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }

    pub(crate) fn bytes(&mut self, b: &[u8]) {
        self.buf.extend_from_slice(b);
    }

    pub(crate) fn varint(&mut self, mut v: u64) {
        while v >= 0x80 {
            self.buf.push((v as u8) | 0x80);
            v >>= 7;
        }
        self.buf.push(v as u8);
    }

    pub(crate) fn zigzag(&mut self, v: i64) {
        self.varint(((v << 1) ^ (v >> 63)) as u64);
    }

    /// Appends a `u32 LE` length followed by `section`.
    pub(crate) fn section(&mut self, section: &[u8]) {
        // Encoders reject anything near 4 GiB long before this (limits are far lower).
        self.u32(u32::try_from(section.len()).expect("section under 4 GiB"));
        self.bytes(section);
    }

    /// Appends the CRC-32 of everything written so far.
    pub(crate) fn checksum(&mut self) {
        let c = crc32(&self.buf);
        self.u32(c);
    }
}

/// Reads a byte slice front to back, naming the section and the absolute offset in errors.
pub(crate) struct Reader<'a> {
    buf: &'a [u8],
    pos: usize,
    /// Absolute offset of `buf[0]` in the whole input.
    base: usize,
    section: &'static str,
    /// Element index appended to the section name (`event 17`), if any.
    index: Option<u64>,
}

impl<'a> Reader<'a> {
    /// A reader over `buf`, which starts at absolute offset `base`.
    pub(crate) fn new(buf: &'a [u8], base: usize, section: &'static str) -> Reader<'a> {
        Reader {
            buf,
            pos: 0,
            base,
            section,
            index: None,
        }
    }

    /// Names the part being read from now on.
    pub(crate) fn enter(&mut self, section: &'static str, index: Option<u64>) {
        self.section = section;
        self.index = index;
    }

    /// Absolute offset of the next byte.
    pub(crate) fn offset(&self) -> usize {
        self.base + self.pos
    }

    pub(crate) fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    /// Fails unless `count` elements of at least `min_bytes` each fit in what is left (the
    /// error at offset `at`, where the count was read), so no count can make a decoder
    /// allocate more than the input justifies.
    pub(crate) fn check_fits(
        &self,
        at: usize,
        count: u64,
        min_bytes: usize,
    ) -> Result<(), DecodeError> {
        let needed = count.saturating_mul(min_bytes as u64);
        if needed > self.remaining() as u64 {
            return Err(self.error_at(
                at,
                DecodeErrorKind::Truncated {
                    needed: usize::try_from(needed).unwrap_or(usize::MAX),
                    available: self.remaining(),
                },
            ));
        }
        Ok(())
    }

    /// An error at the current position.
    pub(crate) fn error(&self, kind: DecodeErrorKind) -> DecodeError {
        self.error_at(self.offset(), kind)
    }

    /// An error at absolute offset `offset`, in the current section.
    pub(crate) fn error_at(&self, offset: usize, kind: DecodeErrorKind) -> DecodeError {
        let section: Cow<'static, str> = match self.index {
            Some(i) => Cow::Owned(format!("{} {i}", self.section)),
            None => Cow::Borrowed(self.section),
        };
        DecodeError::new(section, offset, kind)
    }

    pub(crate) fn malformed(&self, detail: impl Into<String>) -> DecodeError {
        self.error(DecodeErrorKind::Malformed {
            detail: detail.into(),
        })
    }

    /// The next `n` bytes.
    pub(crate) fn take(&mut self, n: usize) -> Result<&'a [u8], DecodeError> {
        if n > self.remaining() {
            return Err(self.error(DecodeErrorKind::Truncated {
                needed: n,
                available: self.remaining(),
            }));
        }
        let s = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], DecodeError> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.take(N)?);
        Ok(a)
    }

    pub(crate) fn u8(&mut self) -> Result<u8, DecodeError> {
        Ok(self.array::<1>()?[0])
    }

    pub(crate) fn u16(&mut self) -> Result<u16, DecodeError> {
        self.array().map(u16::from_le_bytes)
    }

    pub(crate) fn u32(&mut self) -> Result<u32, DecodeError> {
        self.array().map(u32::from_le_bytes)
    }

    pub(crate) fn u64(&mut self) -> Result<u64, DecodeError> {
        self.array().map(u64::from_le_bytes)
    }

    /// An unsigned LEB128 varint of at most 64 bits, in its shortest form.
    pub(crate) fn varint(&mut self) -> Result<u64, DecodeError> {
        let start = self.offset();
        let mut v = 0u64;
        for i in 0..10 {
            let b = self.u8()?;
            // The tenth byte holds bit 63 only.
            if i == 9 && b > 1 {
                return Err(self.error_at(start, malformed("varint overflows 64 bits")));
            }
            v |= u64::from(b & 0x7f) << (7 * i);
            if b & 0x80 == 0 {
                if b == 0 && i > 0 {
                    return Err(self.error_at(start, malformed("varint is not in shortest form")));
                }
                return Ok(v);
            }
        }
        unreachable!("the tenth byte either ends the varint or is rejected")
    }

    /// A varint that must fit in `max` (inclusive); `what` names it in the error.
    pub(crate) fn varint_max(&mut self, what: &'static str, max: u64) -> Result<u64, DecodeError> {
        let start = self.offset();
        let v = self.varint()?;
        if v > max {
            return Err(self.error_at(
                start,
                DecodeErrorKind::TooLarge {
                    what,
                    value: v,
                    limit: max,
                },
            ));
        }
        Ok(v)
    }

    /// A varint that must fit in a `u32`.
    pub(crate) fn varint_u32(&mut self, what: &'static str) -> Result<u32, DecodeError> {
        // The bound makes the conversion exact.
        self.varint_max(what, u32::MAX.into()).map(|v| v as u32)
    }

    /// A zigzag-encoded signed varint.
    pub(crate) fn zigzag(&mut self) -> Result<i64, DecodeError> {
        let u = self.varint()?;
        Ok(((u >> 1) as i64) ^ -((u & 1) as i64))
    }

    /// A `u32 LE` length, then a sub-reader over that many bytes (named `section`).
    /// A length beyond `max` is [`DecodeErrorKind::TooLarge`]; beyond the input, truncated.
    pub(crate) fn section(
        &mut self,
        section: &'static str,
        max: usize,
    ) -> Result<Reader<'a>, DecodeError> {
        self.enter(section, None);
        let len = self.u32()? as usize;
        if len > max {
            return Err(self.error_at(
                self.offset() - 4,
                DecodeErrorKind::TooLarge {
                    what: "section length",
                    value: len as u64,
                    limit: max as u64,
                },
            ));
        }
        let base = self.offset();
        Ok(Reader::new(self.take(len)?, base, section))
    }

    /// Fails unless every byte was read.
    pub(crate) fn finish(&self) -> Result<(), DecodeError> {
        match self.remaining() {
            0 => Ok(()),
            count => Err(self.error(DecodeErrorKind::TrailingBytes { count })),
        }
    }

    /// Decodes a postcard value from the rest of the reader; it must use every byte.
    pub(crate) fn postcard<T: serde::de::DeserializeOwned>(&mut self) -> Result<T, DecodeError> {
        let start = self.offset();
        let (value, rest) = postcard::take_from_bytes::<T>(&self.buf[self.pos..]).map_err(|e| {
            // Postcard does not say where it failed: report the start of the value.
            self.error_at(start, malformed(format!("postcard: {e}")))
        })?;
        self.pos = self.buf.len() - rest.len();
        self.finish()?;
        Ok(value)
    }
}

/// A [`DecodeErrorKind::Malformed`] with `detail`.
pub(crate) fn malformed(detail: impl Into<String>) -> DecodeErrorKind {
    DecodeErrorKind::Malformed {
        detail: detail.into(),
    }
}

/// Reads a fixed magic; a mismatch is [`DecodeErrorKind::BadMagic`].
pub(crate) fn expect_magic(r: &mut Reader<'_>, magic: &'static [u8]) -> Result<(), DecodeError> {
    r.enter("magic", None);
    let n = magic.len().min(r.remaining());
    let found = &r.buf[r.pos..r.pos + n];
    if found != magic {
        // A prefix of the magic is a truncated file, anything else is another format.
        if magic.starts_with(found) {
            return Err(r.error(DecodeErrorKind::Truncated {
                needed: magic.len(),
                available: n,
            }));
        }
        return Err(r.error(DecodeErrorKind::BadMagic {
            expected: magic,
            found: found.to_vec(),
        }));
    }
    r.take(n).map(drop)
}

/// Splits `bytes` into the covered part and the stored trailing CRC-32 and checks it.
/// `covered_len` is where the framing says the checksum starts.
pub(crate) fn check_crc(bytes: &[u8], covered_len: usize) -> Result<(), DecodeError> {
    let mut r = Reader::new(&bytes[covered_len..], covered_len, "checksum");
    let stored = r.u32()?;
    r.finish()?;
    let computed = crc32(&bytes[..covered_len]);
    if stored != computed {
        return Err(DecodeError::new(
            "checksum",
            covered_len,
            DecodeErrorKind::ChecksumMismatch { stored, computed },
        ));
    }
    Ok(())
}

/// Rejects inputs longer than the limit before looking at them.
pub(crate) fn check_len(bytes: &[u8], limits: &DecodeLimits) -> Result<(), DecodeError> {
    if bytes.len() > limits.max_bytes {
        return Err(DecodeError::new(
            "file",
            0,
            DecodeErrorKind::TooLarge {
                what: "input length",
                value: bytes.len() as u64,
                limit: limits.max_bytes as u64,
            },
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varints_round_trip_and_reject_overlong_forms() {
        let values = [
            0u64,
            1,
            127,
            128,
            300,
            16_383,
            16_384,
            u32::MAX.into(),
            u64::MAX,
        ];
        for v in values {
            let mut w = Writer::default();
            w.varint(v);
            assert_eq!(
                w.buf.len(),
                (64 - (v | 1).leading_zeros() as usize).div_ceil(7),
                "{v}"
            );
            let mut r = Reader::new(&w.buf, 0, "t");
            assert_eq!(r.varint().unwrap(), v);
            r.finish().unwrap();
        }
        for v in [0i64, -1, 1, -64, 64, i64::MIN, i64::MAX] {
            let mut w = Writer::default();
            w.zigzag(v);
            assert_eq!(Reader::new(&w.buf, 0, "t").zigzag().unwrap(), v);
        }
        let overlong = [0x80, 0x00];
        let e = Reader::new(&overlong, 5, "t").varint().unwrap_err();
        assert_eq!((e.section.as_ref(), e.offset), ("t", 5));
        let overflow = [0xff; 10];
        assert!(Reader::new(&overflow, 0, "t").varint().is_err());
        let cut = [0x80];
        let e = Reader::new(&cut, 0, "t").varint().unwrap_err();
        assert!(matches!(e.kind, DecodeErrorKind::Truncated { .. }));
    }

    #[test]
    fn errors_name_indexed_sections() {
        let mut r = Reader::new(&[], 9, "x");
        r.enter("event", Some(17));
        let e = r.u8().unwrap_err();
        assert_eq!(e.section, "event 17");
        assert!(
            e.to_string().starts_with("event 17 at byte 9: truncated"),
            "{e}"
        );
    }
}
