//! Lines of text drawn over a frame: a 3x5 pixel font of our own (capitals, digits and
//! a little punctuation; lower case is drawn as capitals), each font pixel 2x2 screen
//! pixels, white on a darkened strip at the bottom of the frame.

use crate::Frame;

/// Screen pixels per font pixel.
const SCALE: usize = 2;
/// A character cell: 3 font pixels and 1 of space across, 5 and 2 down.
const CELL_W: usize = 4 * SCALE;
const CELL_H: usize = 7 * SCALE;
/// Margin around the text inside the strip.
const MARGIN: usize = 2 * SCALE;

/// The glyphs: five rows of three pixels, the top row first, bit 2 the left pixel.
const GLYPHS: &[(char, [u8; 5])] = &[
    ('A', [0b010, 0b101, 0b111, 0b101, 0b101]),
    ('B', [0b110, 0b101, 0b110, 0b101, 0b110]),
    ('C', [0b011, 0b100, 0b100, 0b100, 0b011]),
    ('D', [0b110, 0b101, 0b101, 0b101, 0b110]),
    ('E', [0b111, 0b100, 0b110, 0b100, 0b111]),
    ('F', [0b111, 0b100, 0b110, 0b100, 0b100]),
    ('G', [0b011, 0b100, 0b101, 0b101, 0b011]),
    ('H', [0b101, 0b101, 0b111, 0b101, 0b101]),
    ('I', [0b111, 0b010, 0b010, 0b010, 0b111]),
    ('J', [0b001, 0b001, 0b001, 0b101, 0b010]),
    ('K', [0b101, 0b101, 0b110, 0b101, 0b101]),
    ('L', [0b100, 0b100, 0b100, 0b100, 0b111]),
    ('M', [0b101, 0b111, 0b111, 0b101, 0b101]),
    ('N', [0b110, 0b101, 0b101, 0b101, 0b101]),
    ('O', [0b010, 0b101, 0b101, 0b101, 0b010]),
    ('P', [0b110, 0b101, 0b110, 0b100, 0b100]),
    ('Q', [0b010, 0b101, 0b101, 0b110, 0b011]),
    ('R', [0b110, 0b101, 0b110, 0b101, 0b101]),
    ('S', [0b011, 0b100, 0b010, 0b001, 0b110]),
    ('T', [0b111, 0b010, 0b010, 0b010, 0b010]),
    ('U', [0b101, 0b101, 0b101, 0b101, 0b111]),
    ('V', [0b101, 0b101, 0b101, 0b101, 0b010]),
    ('W', [0b101, 0b101, 0b111, 0b111, 0b101]),
    ('X', [0b101, 0b101, 0b010, 0b101, 0b101]),
    ('Y', [0b101, 0b101, 0b010, 0b010, 0b010]),
    ('Z', [0b111, 0b001, 0b010, 0b100, 0b111]),
    ('0', [0b111, 0b101, 0b101, 0b101, 0b111]),
    ('1', [0b010, 0b110, 0b010, 0b010, 0b111]),
    ('2', [0b110, 0b001, 0b010, 0b100, 0b111]),
    ('3', [0b110, 0b001, 0b010, 0b001, 0b110]),
    ('4', [0b101, 0b101, 0b111, 0b001, 0b001]),
    ('5', [0b111, 0b100, 0b110, 0b001, 0b110]),
    ('6', [0b011, 0b100, 0b111, 0b101, 0b111]),
    ('7', [0b111, 0b001, 0b010, 0b010, 0b010]),
    ('8', [0b111, 0b101, 0b111, 0b101, 0b111]),
    ('9', [0b111, 0b101, 0b111, 0b001, 0b110]),
    ('/', [0b001, 0b001, 0b010, 0b100, 0b100]),
    (':', [0b000, 0b010, 0b000, 0b010, 0b000]),
    (',', [0b000, 0b000, 0b000, 0b010, 0b100]),
    ('.', [0b000, 0b000, 0b000, 0b000, 0b010]),
    ('-', [0b000, 0b000, 0b111, 0b000, 0b000]),
    ('_', [0b000, 0b000, 0b000, 0b000, 0b111]),
    ('(', [0b001, 0b010, 0b010, 0b010, 0b001]),
    (')', [0b100, 0b010, 0b010, 0b010, 0b100]),
    ('|', [0b010, 0b010, 0b010, 0b010, 0b010]),
    ('?', [0b110, 0b001, 0b010, 0b000, 0b010]),
];

/// The glyph of `c`: capitals for lower case; a box for a character the font lacks
/// (a space is blank).
fn glyph(c: char) -> [u8; 5] {
    if c == ' ' {
        return [0; 5];
    }
    let c = c.to_ascii_uppercase();
    GLYPHS
        .iter()
        .find(|(g, _)| *g == c)
        .map_or([0b111, 0b101, 0b101, 0b101, 0b111], |(_, rows)| *rows)
}

/// How many characters fit on a line of a frame `width` pixels wide.
pub fn columns(width: usize) -> usize {
    width.saturating_sub(2 * MARGIN) / CELL_W
}

/// Breaks `text` into lines of at most `columns` characters at spaces (a word longer
/// than a line is cut).
pub fn wrap(text: &str, columns: usize) -> Vec<String> {
    let columns = columns.max(1);
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split(' ').filter(|w| !w.is_empty()) {
        let mut word: Vec<char> = word.chars().collect();
        loop {
            let used = line.chars().count();
            let room = if used == 0 {
                columns
            } else {
                columns.saturating_sub(used + 1)
            };
            if word.len() <= room {
                if used > 0 {
                    line.push(' ');
                }
                line.extend(word.iter());
                break;
            }
            if used > 0 {
                lines.push(std::mem::take(&mut line));
                continue;
            }
            line.extend(word.drain(..columns));
            lines.push(std::mem::take(&mut line));
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draws `lines` at the bottom of `frame` over a strip darkened to a quarter of its
/// brightness; lines past the frame's height and characters past its width are left
/// out.
pub fn draw_lines(frame: &mut Frame, lines: &[String]) {
    if frame.pixels.len() < frame.width.saturating_mul(frame.height) {
        return; // not a whole frame
    }
    let strip = (lines.len() * CELL_H + 2 * MARGIN).min(frame.height);
    let top = frame.height - strip;
    for y in top..frame.height {
        for p in &mut frame.pixels[y * frame.width..(y + 1) * frame.width] {
            *p = (*p >> 2) & 0x003f_3f3f;
        }
    }
    for (row, line) in lines.iter().enumerate() {
        let y0 = top + MARGIN + row * CELL_H;
        for (col, c) in line.chars().enumerate().take(columns(frame.width)) {
            let x0 = MARGIN + col * CELL_W;
            for (gy, bits) in glyph(c).iter().enumerate() {
                for gx in 0..3 {
                    if bits & (0b100 >> gx) == 0 {
                        continue;
                    }
                    for dy in 0..SCALE {
                        let y = y0 + gy * SCALE + dy;
                        if y >= frame.height {
                            continue;
                        }
                        let x = x0 + gx * SCALE;
                        for p in &mut frame.pixels[y * frame.width + x..][..SCALE] {
                            *p = 0x00ff_ffff;
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_wrap_at_spaces_and_cut_long_words() {
        assert_eq!(wrap("ab cd ef", 5), ["ab cd", "ef"]);
        assert_eq!(wrap("abcdefg hi", 3), ["abc", "def", "g", "hi"]);
        assert_eq!(wrap("  a  ", 4), ["a"]);
        assert!(wrap("", 4).is_empty());
    }

    #[test]
    fn a_glyph_lands_white_on_a_darkened_strip() {
        let mut frame = Frame {
            width: 20,
            height: 30,
            pixels: vec![0x0080_8080; 600],
        };
        draw_lines(&mut frame, &["I".to_string()]);
        let at = |x: usize, y: usize| frame.pixels[y * 20 + x];
        // The strip: one line of 14 rows and margins of 4, rows 8 to 29.
        assert_eq!(at(5, 7), 0x0080_8080);
        assert_eq!(at(19, 8), 0x0020_2020);
        // "I": its top row three font pixels across from (4, 12), each 2x2.
        for x in 4..10 {
            assert_eq!(at(x, 12), 0x00ff_ffff, "x {x}");
            assert_eq!(at(x, 13), 0x00ff_ffff, "x {x}");
        }
        assert_eq!(at(10, 12), 0x0020_2020);
        // Its second row: the middle pixel only.
        assert_eq!(at(4, 14), 0x0020_2020);
        assert_eq!(at(6, 14), 0x00ff_ffff);
        assert_eq!(at(8, 15), 0x0020_2020);
        assert_eq!(columns(20), 1);
    }

    #[test]
    fn lower_case_is_capitals_and_unknown_is_a_box() {
        assert_eq!(glyph('a'), glyph('A'));
        assert_eq!(glyph('~'), [0b111, 0b101, 0b101, 0b101, 0b111]);
        assert_eq!(glyph(' '), [0; 5]);
    }

    #[test]
    fn more_lines_than_fit_are_clipped() {
        let mut frame = Frame {
            width: 8,
            height: 6,
            pixels: vec![0x00ff_ffff; 48],
        };
        draw_lines(&mut frame, &["WWWW".to_string(), "W".to_string()]);
        assert_eq!(frame.pixels.len(), 48);
    }
}
