//! Small PNG charts drawn straight into an RGB image (no plotting library, no font file):
//! axes, grid lines, points, lines, bars and labels in a built-in 3x5 pixel font, scaled.
//! Enough for the charts of `voodoo bench --chart`; nothing here knows what is plotted.

use image::{Rgb, RgbImage};

/// Colours of the methods in every chart, in `sst1_board::Method::ALL` order.
pub const METHOD_COLOURS: [[u8; 3]; 6] = [
    [0, 0, 0],
    [128, 128, 128],
    [214, 39, 40],
    [31, 119, 180],
    [44, 160, 44],
    [255, 127, 14],
];

/// The 3x5 glyph of `c` (rows top first, bit 2 the left column); lowercase letters are
/// drawn as capitals, anything unknown as a blank.
fn glyph(c: char) -> [u8; 5] {
    match c.to_ascii_uppercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 3, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 2, 2],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        'A' => [2, 5, 7, 5, 5],
        'B' => [6, 5, 6, 5, 6],
        'C' => [3, 4, 4, 4, 3],
        'D' => [6, 5, 5, 5, 6],
        'E' => [7, 4, 6, 4, 7],
        'F' => [7, 4, 6, 4, 4],
        'G' => [3, 4, 5, 5, 3],
        'H' => [5, 5, 7, 5, 5],
        'I' => [7, 2, 2, 2, 7],
        'J' => [1, 1, 1, 5, 2],
        'K' => [5, 5, 6, 5, 5],
        'L' => [4, 4, 4, 4, 7],
        'M' => [5, 7, 7, 5, 5],
        'N' => [6, 5, 5, 5, 5],
        'O' => [2, 5, 5, 5, 2],
        'P' => [6, 5, 6, 4, 4],
        'Q' => [2, 5, 5, 6, 3],
        'R' => [6, 5, 6, 5, 5],
        'S' => [3, 4, 2, 1, 6],
        'T' => [7, 2, 2, 2, 2],
        'U' => [5, 5, 5, 5, 7],
        'V' => [5, 5, 5, 5, 2],
        'W' => [5, 5, 7, 7, 5],
        'X' => [5, 5, 2, 5, 5],
        'Y' => [5, 5, 2, 2, 2],
        'Z' => [7, 1, 2, 4, 7],
        '.' => [0, 0, 0, 0, 2],
        ',' => [0, 0, 0, 2, 4],
        '-' => [0, 0, 7, 0, 0],
        '+' => [0, 2, 7, 2, 0],
        '_' => [0, 0, 0, 0, 7],
        '=' => [0, 7, 0, 7, 0],
        '%' => [5, 1, 2, 4, 5],
        '/' => [1, 1, 2, 4, 4],
        ':' => [0, 2, 0, 2, 0],
        '(' => [1, 2, 2, 2, 1],
        ')' => [4, 2, 2, 2, 4],
        '<' => [1, 2, 4, 2, 1],
        '>' => [4, 2, 1, 2, 4],
        '^' => [2, 5, 0, 0, 0],
        _ => [0; 5],
    }
}

/// A chart being drawn: the image and the plot area's pixel rectangle.
pub struct Canvas {
    pub img: RgbImage,
}

/// Scale of the font: each glyph cell 2x2 pixels (glyphs 6x10, 8 px apart).
const FONT: u32 = 2;

impl Canvas {
    /// A white canvas.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            img: RgbImage::from_pixel(width.max(1), height.max(1), Rgb([255, 255, 255])),
        }
    }

    /// Sets one pixel; outside the image does nothing.
    pub fn put(&mut self, x: i64, y: i64, c: [u8; 3]) {
        if x >= 0 && y >= 0 && (x as u32) < self.img.width() && (y as u32) < self.img.height() {
            self.img.put_pixel(x as u32, y as u32, Rgb(c));
        }
    }

    /// A filled rectangle, corners included.
    pub fn rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: [u8; 3]) {
        let (x0, x1) = (x0.min(x1), x0.max(x1));
        let (y0, y1) = (y0.min(y1), y0.max(y1));
        let w = i64::from(self.img.width());
        let h = i64::from(self.img.height());
        for y in y0.max(0)..=y1.min(h - 1) {
            for x in x0.max(0)..=x1.min(w - 1) {
                self.put(x, y, c);
            }
        }
    }

    /// A line one pixel wide (Bresenham), ends included.
    pub fn line(&mut self, (x0, y0): (i64, i64), (x1, y1): (i64, i64), c: [u8; 3]) {
        let (dx, dy) = ((x1 - x0).abs(), -(y1 - y0).abs());
        let (sx, sy) = (if x0 < x1 { 1 } else { -1 }, if y0 < y1 { 1 } else { -1 });
        let (mut x, mut y, mut err) = (x0, y0, dx + dy);
        // At most one step per pixel of the longer side: a far-off end cannot loop long.
        for _ in 0..=dx.max(-dy).min(1 << 16) {
            self.put(x, y, c);
            if x == x1 && y == y1 {
                break;
            }
            let e2 = 2 * err;
            if e2 >= dy {
                err += dy;
                x += sx;
            }
            if e2 <= dx {
                err += dx;
                y += sy;
            }
        }
    }

    /// A filled square marker of half-size `r` centred on `(x, y)`.
    pub fn marker(&mut self, x: i64, y: i64, r: i64, c: [u8; 3]) {
        self.rect(x - r, y - r, x + r, y + r, c);
    }

    /// `text` with its top left corner at `(x, y)`.
    pub fn text(&mut self, x: i64, y: i64, text: &str, c: [u8; 3]) {
        let s = i64::from(FONT);
        for (i, ch) in text.chars().enumerate() {
            let rows = glyph(ch);
            let gx = x + i as i64 * 4 * s;
            for (row, bits) in rows.iter().enumerate() {
                for col in 0..3 {
                    if bits >> (2 - col) & 1 == 1 {
                        let px = gx + col * s;
                        let py = y + row as i64 * s;
                        self.rect(px, py, px + s - 1, py + s - 1, c);
                    }
                }
            }
        }
    }

    /// Width in pixels of `text` as [`Canvas::text`] draws it.
    pub fn text_width(text: &str) -> i64 {
        text.chars().count() as i64 * 4 * i64::from(FONT)
    }

    /// The PNG file's bytes.
    pub fn png(&self) -> Result<Vec<u8>, String> {
        let mut out = std::io::Cursor::new(Vec::new());
        self.img
            .write_to(&mut out, image::ImageFormat::Png)
            .map_err(|e| e.to_string())?;
        Ok(out.into_inner())
    }
}

/// A plot area inside a canvas: pixel rectangle `x0..=x1`, `y0..=y1` (y0 the top) and the
/// data range it shows.
#[derive(Clone, Copy)]
pub struct Area {
    pub x0: i64,
    pub y0: i64,
    pub x1: i64,
    pub y1: i64,
    /// Data x at the left and right edge.
    pub xr: (f64, f64),
    /// Data y at the bottom and top edge.
    pub yr: (f64, f64),
}

impl Area {
    /// The pixel of data point `(x, y)`, clamped into the area.
    pub fn at(&self, x: f64, y: f64) -> (i64, i64) {
        let fx = ((x - self.xr.0) / (self.xr.1 - self.xr.0)).clamp(0.0, 1.0);
        let fy = ((y - self.yr.0) / (self.yr.1 - self.yr.0)).clamp(0.0, 1.0);
        let fx = if fx.is_nan() { 0.0 } else { fx };
        let fy = if fy.is_nan() { 0.0 } else { fy };
        (
            self.x0 + (fx * (self.x1 - self.x0) as f64).round() as i64,
            self.y1 - (fy * (self.y1 - self.y0) as f64).round() as i64,
        )
    }

    /// The frame, light grid lines at `xticks` and `yticks` (data values) with their
    /// labels, and a title above.
    pub fn frame(
        &self,
        c: &mut Canvas,
        xticks: &[(f64, String)],
        yticks: &[(f64, String)],
        title: &str,
    ) {
        let grid = [225, 225, 225];
        let ink = [40, 40, 40];
        for (x, label) in xticks {
            let (px, _) = self.at(*x, self.yr.0);
            c.line((px, self.y0), (px, self.y1), grid);
            c.text(px - Canvas::text_width(label) / 2, self.y1 + 6, label, ink);
        }
        for (y, label) in yticks {
            let (_, py) = self.at(self.xr.0, *y);
            c.line((self.x0, py), (self.x1, py), grid);
            c.text(self.x0 - Canvas::text_width(label) - 6, py - 5, label, ink);
        }
        c.line((self.x0, self.y0), (self.x0, self.y1), ink);
        c.line((self.x0, self.y1), (self.x1, self.y1), ink);
        c.line((self.x1, self.y0), (self.x1, self.y1), ink);
        c.line((self.x0, self.y0), (self.x1, self.y0), ink);
        c.text(self.x0, self.y0 - 16, title, ink);
    }
}

#[cfg(test)]
mod tests {
    use super::{Area, Canvas};

    #[test]
    fn areas_map_data_to_pixels_and_text_lands_where_asked() {
        let a = Area {
            x0: 10,
            y0: 10,
            x1: 110,
            y1: 60,
            xr: (0.0, 1.0),
            yr: (0.0, 50.0),
        };
        assert_eq!(a.at(0.0, 0.0), (10, 60));
        assert_eq!(a.at(1.0, 50.0), (110, 10));
        assert_eq!(a.at(0.5, 25.0), (60, 35));
        // Out of range and NaN are clamped to the area.
        assert_eq!(a.at(9.0, f64::NAN), (110, 60));
        let mut c = Canvas::new(40, 20);
        c.text(0, 0, "1", [0, 0, 0]);
        // '1' is rows 010/110/010/010/111: top row middle column set, left clear.
        assert_eq!(c.img.get_pixel(2, 0).0, [0, 0, 0]);
        assert_eq!(c.img.get_pixel(0, 0).0, [255, 255, 255]);
        assert_eq!(c.img.get_pixel(0, 9).0, [0, 0, 0]);
        assert_eq!(Canvas::text_width("abc"), 24);
        c.line((0, 19), (39, 19), [1, 2, 3]);
        assert_eq!(c.img.get_pixel(39, 19).0, [1, 2, 3]);
        assert!(c.png().unwrap().starts_with(b"\x89PNG"));
    }
}
