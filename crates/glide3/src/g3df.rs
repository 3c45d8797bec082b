//! `.3DF` texture files: `gu3dfGetInfo` and `gu3dfLoad`.
//!
//! Format (3dfx's SST-1 Glide 3 g3df.c, read for facts; the test textures of
//! glide3x/sst1/glide3/tests agree): four text lines,
//!
//! ```text
//! 3df v1.1
//! rgb565
//! lod range: 1 256
//! aspect ratio: 1 1
//! ```
//!
//! (version, format name in any case, smallest and largest LOD as texel counts,
//! aspect ratio as width height), each ending in `\n`, 99 characters in all at most.
//! Then, big-endian: for YIQ/AYIQ formats an NCC table (16 Y, 12 I, 12 Q values as
//! 16-bit words), for P8/AP88 a 256-entry palette (32-bit words); then every mipmap
//! level from the largest down, 8-bit texels as bytes, 16-bit texels as big-endian
//! words.

use crate::consts::*;
use crate::tex::level_wh;

/// Why a `.3DF` file was refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Error3df {
    /// The four header lines are missing, too long or not in the expected form.
    Header,
    /// The aspect ratio is not 1:1, 2:1, 4:1 or 8:1 either way.
    AspectRatio,
    /// A LOD is not a power of two from 1 to 256.
    Lod,
    /// The format name is not one of the 13 3dfx lists.
    Format,
    /// The file ends before the table or the texels do.
    Truncated,
}

impl std::fmt::Display for Error3df {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Error3df::Header => "bad .3df header",
            Error3df::AspectRatio => "unsupported .3df aspect ratio",
            Error3df::Lod => "unsupported .3df LOD",
            Error3df::Format => "unknown .3df texture format",
            Error3df::Truncated => ".3df file too short",
        })
    }
}

impl std::error::Error for Error3df {}

/// `Gu3dfHeader`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Gu3dfHeader {
    /// Width of the largest level in texels.
    pub width: u32,
    /// Height of the largest level in texels.
    pub height: u32,
    /// Smallest level, `GR_LOD_LOG2_*`.
    pub small_lod: u32,
    /// Largest level, `GR_LOD_LOG2_*`.
    pub large_lod: u32,
    /// `GR_ASPECT_LOG2_*` (log2 of width / height).
    pub aspect: i32,
    /// `GR_TEXFMT_*`.
    pub format: u32,
}

/// `gu3dfGetInfo`'s answer: the header and the bytes the texels need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Gu3dfInfo {
    /// The parsed header.
    pub header: Gu3dfHeader,
    /// Bytes of every level, as `grTexDownloadMipMap` takes them.
    pub mem_required: u32,
}

/// `GuNccTable`: the YIQ decompression table of a `.3DF` file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NccTable {
    /// Y entries.
    pub y: [u8; 16],
    /// I entries, 9 bits each (r, g, b).
    pub i: [[i16; 3]; 4],
    /// Q entries, 9 bits each (r, g, b).
    pub q: [[i16; 3]; 4],
    /// The 12 register words (`nccTable0/1`).
    pub packed: [u32; 12],
}

/// The table a `.3DF` file carries for its format.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TexTable {
    /// No table (RGB, alpha and intensity formats).
    None,
    /// YIQ_422 / AYIQ_8422.
    Ncc(NccTable),
    /// P_8 / AP_88: 256 entries 0x00RRGGBB (top byte as stored).
    Palette(Box<[u32; 256]>),
}

/// Format names and their `GR_TEXFMT_*` (g3df.c `cftable`).
const FORMATS: [(&str, u32); 13] = [
    ("I8", GR_TEXFMT_INTENSITY_8),
    ("A8", GR_TEXFMT_ALPHA_8),
    ("AI44", GR_TEXFMT_ALPHA_INTENSITY_44),
    ("YIQ", GR_TEXFMT_YIQ_422),
    ("RGB332", GR_TEXFMT_RGB_332),
    ("RGB565", GR_TEXFMT_RGB_565),
    ("ARGB8332", GR_TEXFMT_ARGB_8332),
    ("ARGB1555", GR_TEXFMT_ARGB_1555),
    ("AYIQ8422", GR_TEXFMT_AYIQ_8422),
    ("ARGB4444", GR_TEXFMT_ARGB_4444),
    ("AI88", GR_TEXFMT_ALPHA_INTENSITY_88),
    ("P8", GR_TEXFMT_P_8),
    ("AP88", GR_TEXFMT_AP_88),
];

/// Most bytes the four header lines of a `.3DF` file take: 3dfx reads them with `fgets`
/// into a 100-byte buffer. [`get_info`] needs no more of a file than this.
pub const MAX_HEADER_BYTES: usize = 99;

/// Most bytes of a file [`load`] reads: the header, the largest table (a palette, 256
/// big-endian words) and the largest mipmap (256x256 down to 1x1, 16-bit texels).
pub const MAX_FILE_BYTES: usize = MAX_HEADER_BYTES + 256 * 4 + 2 * 87_381;

/// The four header lines and the offset of the data after them (at most
/// [`MAX_HEADER_BYTES`]).
fn header_lines(file: &[u8]) -> Result<(&str, usize), Error3df> {
    let mut end = 0;
    for _ in 0..4 {
        let nl = file[end..]
            .iter()
            .position(|&b| b == b'\n')
            .ok_or(Error3df::Header)?;
        end += nl + 1;
    }
    if end > MAX_HEADER_BYTES {
        return Err(Error3df::Header);
    }
    let text = std::str::from_utf8(&file[..end]).map_err(|_| Error3df::Header)?;
    Ok((text, end))
}

/// A `%i` number: optional sign, then `0x` hex, `0` octal or decimal.
fn c_int(s: &str) -> Option<i64> {
    let (neg, s) = match s.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, s.strip_prefix('+').unwrap_or(s)),
    };
    let v = if let Some(h) = s.strip_prefix("0x").or_else(|| s.strip_prefix("0X")) {
        i64::from_str_radix(h, 16).ok()?
    } else if s.len() > 1 && s.starts_with('0') {
        i64::from_str_radix(&s[1..], 8).ok()?
    } else {
        s.parse().ok()?
    };
    Some(if neg { -v } else { v })
}

/// `GR_LOD_LOG2_*` of a LOD given as a texel count.
fn lod_log2(n: i64) -> Result<u32, Error3df> {
    match n {
        1 | 2 | 4 | 8 | 16 | 32 | 64 | 128 | 256 => Ok(n.trailing_zeros()),
        _ => Err(Error3df::Lod),
    }
}

/// Bytes of levels `small..=large` of a texture.
fn mip_bytes(h: &Gu3dfHeader) -> u32 {
    let texel = if h.format >= GR_TEXFMT_16BIT { 2 } else { 1 };
    (h.small_lod..=h.large_lod)
        .map(|l| {
            let (w, hh) = level_wh(l, h.aspect);
            w * hh * texel
        })
        .sum()
}

/// `gu3dfGetInfo`: parse the header of a `.3DF` file.
pub fn get_info(file: &[u8]) -> Result<Gu3dfInfo, Error3df> {
    let (text, _) = header_lines(file)?;
    let t: Vec<&str> = text.split_whitespace().collect();
    let version_ok = t.get(1).is_some_and(|v| v.len() > 1 && v.starts_with('v'));
    if t.len() < 11
        || t[0] != "3df"
        || !version_ok
        || t[3] != "lod"
        || t[4] != "range:"
        || t[7] != "aspect"
        || t[8] != "ratio:"
    {
        return Err(Error3df::Header);
    }
    let num = |i: usize| c_int(t[i]).ok_or(Error3df::Header);
    let (small, large, aw, ah) = (num(5)?, num(6)?, num(9)?, num(10)?);
    // aspect: width:height of 1, 2, 4 or 8 to 1 either way (width first as in 3dfx).
    let aspect: i32 = (0..4)
        .find(|&i| aw > 0 && (aw << i) == ah)
        .map(|i| -i)
        .or_else(|| (0..4).find(|&i| ah > 0 && (ah << i) == aw))
        .ok_or(Error3df::AspectRatio)?;
    let (small_lod, large_lod) = (lod_log2(small)?, lod_log2(large)?);
    let (width, height) = if aw >= ah {
        (large, large / aw)
    } else {
        (large / ah, large)
    };
    let name = t[2].to_ascii_uppercase();
    let format = FORMATS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|&(_, f)| f)
        .ok_or(Error3df::Format)?;
    if small_lod > large_lod {
        return Err(Error3df::Lod);
    }
    let header = Gu3dfHeader {
        width: width as u32,
        height: height as u32,
        small_lod,
        large_lod,
        aspect,
        format,
    };
    Ok(Gu3dfInfo {
        header,
        mem_required: mip_bytes(&header),
    })
}

/// Big-endian reader over the data part of a file.
struct Reader<'a>(&'a [u8]);

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], Error3df> {
        if self.0.len() < n {
            return Err(Error3df::Truncated);
        }
        let (a, b) = self.0.split_at(n);
        self.0 = b;
        Ok(a)
    }
    fn u16(&mut self) -> Result<u16, Error3df> {
        let b = self.take(2)?;
        Ok(u16::from_be_bytes([b[0], b[1]]))
    }
    fn u32(&mut self) -> Result<u32, Error3df> {
        let b = self.take(4)?;
        Ok(u32::from_be_bytes([b[0], b[1], b[2], b[3]]))
    }
}

/// `gu3dfLoad`: the table and the texels (every level, largest first; 16-bit texels
/// in host byte order, ready for `grTexDownloadMipMap`) of a file whose header
/// `get_info` returned. As in 3dfx's library, the table and texel layout follow
/// `header` (the caller's copy), not a second parse of the file's header.
pub fn load(file: &[u8], header: &Gu3dfHeader) -> Result<(TexTable, Vec<u8>), Error3df> {
    let (_, start) = header_lines(file)?;
    let mut r = Reader(&file[start..]);
    let table = match header.format {
        GR_TEXFMT_YIQ_422 | GR_TEXFMT_AYIQ_8422 => {
            let mut n = NccTable {
                y: [0; 16],
                i: [[0; 3]; 4],
                q: [[0; 3]; 4],
                packed: [0; 12],
            };
            for y in n.y.iter_mut() {
                *y = r.u16()? as u8;
            }
            for row in n.i.iter_mut().chain(n.q.iter_mut()) {
                for v in row.iter_mut() {
                    *v = (r.u16()? & 0x1ff) as i16;
                }
            }
            for k in 0..4 {
                n.packed[k] = u32::from_le_bytes([
                    n.y[4 * k],
                    n.y[4 * k + 1],
                    n.y[4 * k + 2],
                    n.y[4 * k + 3],
                ]);
                let pack = |e: [i16; 3]| ((e[0] as u32) << 18) | ((e[1] as u32) << 9) | e[2] as u32;
                n.packed[4 + k] = pack(n.i[k]);
                n.packed[8 + k] = pack(n.q[k]);
            }
            TexTable::Ncc(n)
        }
        GR_TEXFMT_P_8 | GR_TEXFMT_AP_88 => {
            let mut p = Box::new([0u32; 256]);
            for e in p.iter_mut() {
                *e = r.u32()?;
            }
            TexTable::Palette(p)
        }
        _ => TexTable::None,
    };
    if header.small_lod > header.large_lod
        || header.large_lod > 8
        || !(-3..=3).contains(&header.aspect)
        || matches!(header.format, GR_TEXFMT_RSVD0 | GR_TEXFMT_RSVD1)
        || header.format > GR_TEXFMT_AP_88
    {
        return Err(Error3df::Format);
    }
    let size = mip_bytes(header) as usize;
    let data = if header.format >= GR_TEXFMT_16BIT {
        let raw = r.take(size)?;
        raw.chunks_exact(2)
            .flat_map(|w| u16::from_be_bytes([w[0], w[1]]).to_ne_bytes())
            .collect()
    } else {
        r.take(size)?.to_vec()
    };
    Ok((table, data))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_read_limit_covers_the_largest_file() {
        let biggest = Gu3dfHeader {
            width: 256,
            height: 256,
            small_lod: 0,
            large_lod: 8,
            aspect: 0,
            format: GR_TEXFMT_AP_88,
        };
        assert_eq!(
            MAX_FILE_BYTES,
            MAX_HEADER_BYTES + 1024 + mip_bytes(&biggest) as usize
        );
        // A header of exactly MAX_HEADER_BYTES is read whole.
        let mut h = b"3df v1.0\nrgb565\nlod range: 1 256\naspect ratio: 1 1".to_vec();
        h.resize(MAX_HEADER_BYTES - 1, b' ');
        h.push(b'\n');
        assert!(get_info(&h).is_ok());
        h.insert(8, b' ');
        assert_eq!(get_info(&h).err(), Some(Error3df::Header));
    }

    #[test]
    fn header_numbers_and_aspects() {
        let i = get_info(b"3df v1.1\nrgb565\nlod range: 1 256\naspect ratio: 8 1\n").unwrap();
        assert_eq!(
            i.header,
            Gu3dfHeader {
                width: 256,
                height: 32,
                small_lod: 0,
                large_lod: 8,
                aspect: 3,
                format: GR_TEXFMT_RGB_565
            }
        );
        // 256x32 + 128x16 + 64x8 + 32x4 + 16x2 + 8x1 + 4x1 + 2x1 + 1x1, 2 bytes each.
        assert_eq!(
            i.mem_required,
            2 * (8192 + 2048 + 512 + 128 + 32 + 8 + 4 + 2 + 1)
        );
        let i = get_info(b"3df v1.0\nai44\nlod range: 0x4 010\naspect ratio: 1 4\n").unwrap();
        assert_eq!((i.header.width, i.header.height), (2, 8));
        assert_eq!((i.header.small_lod, i.header.large_lod), (2, 3));
        assert_eq!(i.header.aspect, -2);
        assert_eq!(i.mem_required, 16 + 4);
    }

    #[test]
    fn bad_headers() {
        let bad = |s: &[u8]| get_info(s).unwrap_err();
        assert_eq!(
            bad(b"3df v1.1\nrgb565\nlod range: 1 256\n"),
            Error3df::Header
        );
        assert_eq!(
            bad(b"3dg v1.1\nrgb565\nlod range: 1 256\naspect ratio: 1 1\n"),
            Error3df::Header
        );
        assert_eq!(
            bad(b"3df v1.1\nrgb565\nlod range: 1 256\naspect ratio: 3 1\n"),
            Error3df::AspectRatio
        );
        assert_eq!(
            bad(b"3df v1.1\nrgb565\nlod range: 1 512\naspect ratio: 1 1\n"),
            Error3df::Lod
        );
        assert_eq!(
            bad(b"3df v1.1\nrgb888\nlod range: 1 256\naspect ratio: 1 1\n"),
            Error3df::Format
        );
        assert_eq!(
            bad(b"3df v1.1\nrgb565\nlod range: 1 256\naspect ratio: 0 0\n"),
            Error3df::AspectRatio
        );
        let mut long = b"3df v1.1\nrgb565\nlod range: 1 256\naspect ratio: 1 1".to_vec();
        long.extend(std::iter::repeat_n(b' ', 60));
        long.push(b'\n');
        assert_eq!(bad(&long), Error3df::Header);
    }
}
