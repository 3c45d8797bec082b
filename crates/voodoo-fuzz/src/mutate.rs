//! Mutations of an input: byte edits, the trace formats' own words, interesting 32-bit
//! values, and splices from another input. Inputs never grow past [`MAX_INPUT`].

use crate::rng::Rng;

/// The largest input a mutation makes, in bytes.
pub const MAX_INPUT: usize = 64 << 10;

/// Words and bytes of the trace formats, for inserting whole.
pub const DICTIONARY: &[&[u8]] = &[
    b"config ",
    b"fbi_mb ",
    b"tmus ",
    b"tmu_mb ",
    b"pci ",
    b"w ",
    b"r ",
    b"dump ",
    b"front ",
    b"back ",
    b"depth ",
    b"aux ",
    b"0x",
    b"0x40 ",
    b"0x000128 ",
    b"0x000124 0\n",
    b"0x00000003",
    b"0xffffffff",
    b"4294967296",
    b"0x1000000",
    b"0xfffffc",
    b"a.raw",
    b"../x",
    b"\n",
    b"\r\n",
    b"# ",
    b"\t",
    b"\xff",
    b"\xc3\xa9",
    b"\0",
    b"SST1TRCB",
    b"\x1f\x8b",
    b"config tmus 3\n",
    b"w 0x000128 1\n",
    b"dump front d.raw\n",
];

/// 32-bit values that sit on the formats' and the board's edges.
pub const INTERESTING: &[u32] = &[
    0,
    1,
    3,
    4,
    0x40,
    0xfc,
    0x100,
    0x124,
    0x128,
    0x3f_fffc,
    0x40_0000,
    0x80_0000,
    0xff_fffc,
    0x100_0000,
    0x7fff_ffff,
    0x8000_0000,
    0xffff_fffc,
    0xffff_ffff,
];

/// Applies one to eight random mutations to `input`; `other` is a second input to splice
/// from.
pub fn mutate(rng: &mut Rng, input: &mut Vec<u8>, other: &[u8]) {
    for _ in 0..1 + rng.below(8) {
        mutate_once(rng, input, other);
    }
    input.truncate(MAX_INPUT);
}

fn mutate_once(rng: &mut Rng, input: &mut Vec<u8>, other: &[u8]) {
    let len = input.len();
    let at = rng.below(len + 1);
    match rng.below(11) {
        0 if at < len => input[at] ^= 1 << rng.below(8),
        1 if at < len => input[at] = rng.next_u32() as u8,
        2 => input.insert(at, rng.next_u32() as u8),
        3 if at < len => {
            let end = (at + 1 + rng.below(16)).min(len);
            input.drain(at..end);
        }
        4 => input.truncate(at),
        5 => {
            if let Some(word) = rng.pick(DICTIONARY) {
                input.splice(at..at, word.iter().copied());
            }
        }
        6 if at + 4 <= len => {
            let value = rng.pick(INTERESTING).copied().unwrap_or(0);
            input[at..at + 4].copy_from_slice(&value.to_le_bytes());
        }
        7 if at < len => {
            // Duplicate a short range (repeats records and lines).
            let end = (at + 1 + rng.below(64)).min(len);
            let piece = input[at..end].to_vec();
            input.splice(at..at, piece);
        }
        8 if !other.is_empty() => {
            // Splice: a piece of the other input replaces our tail.
            let from = rng.below(other.len());
            let to = (from + 1 + rng.below(512)).min(other.len());
            input.truncate(at);
            input.extend_from_slice(&other[from..to]);
        }
        9 if at < len => {
            // Replace a number's digits with another number.
            let value = rng.pick(INTERESTING).copied().unwrap_or(0);
            let text = if rng.one_in(2) {
                format!("{value:#x}")
            } else {
                value.to_string()
            };
            let end = (at + 1 + rng.below(10)).min(len);
            input.splice(at..end, text.into_bytes());
        }
        _ => {
            let random: Vec<u8> = (0..1 + rng.below(8))
                .map(|_| rng.next_u32() as u8)
                .collect();
            input.splice(at..at, random);
        }
    }
}

/// Reads values from an input's bytes, for targets that turn bytes into a sequence of
/// calls (as `arbitrary`'s `Unstructured` does): each read takes bytes from the front,
/// and an exhausted input reads as zeros.
#[derive(Clone, Debug)]
pub struct ByteSource<'a> {
    bytes: &'a [u8],
}

impl<'a> ByteSource<'a> {
    /// A source over `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    /// Whether every byte has been read.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }

    /// The next byte (0 when exhausted).
    pub fn u8(&mut self) -> u8 {
        match self.bytes.split_first() {
            Some((&b, rest)) => {
                self.bytes = rest;
                b
            }
            None => 0,
        }
    }

    /// The next four bytes, little-endian (zeros when exhausted).
    pub fn u32(&mut self) -> u32 {
        u32::from_le_bytes([self.u8(), self.u8(), self.u8(), self.u8()])
    }

    /// A number in `0..n` from the next byte (0 if `n` is 0).
    pub fn below(&mut self, n: u8) -> u8 {
        if n == 0 {
            0
        } else {
            self.u8() % n
        }
    }

    /// The next `n` bytes, or as many as are left.
    pub fn bytes(&mut self, n: usize) -> &'a [u8] {
        let (head, rest) = self.bytes.split_at(n.min(self.bytes.len()));
        self.bytes = rest;
        head
    }
}
