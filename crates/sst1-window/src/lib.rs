//! A window that shows frames of the emulated board (what its monitor would show) and
//! hands back the keys pressed in it: the live window of libglide3 (`VOODOO_WINDOW=1`)
//! and of `voodoo demo` and `voodoo play`.
//!
//! * [`Frame`]: `width * height` pixels in 0x00RRGGBB, made from the board's RGB565
//!   buffers by bit replication ([`Frame::from_rgb565`]). The window scales it to its
//!   own size (nearest pixel); at the frame's own size (where it opens) that is 1:1.
//! * [`Window::open`] starts a session; [`Window::show`] replaces the frame on show
//!   (the caller never waits on the window: a frame the window has not taken yet is
//!   replaced); [`Window::next_event`] waits for a key press or the window's closing.
//!   Dropping the [`Window`] closes it.
//! * Where no window can open, [`Window::open`] returns a [`NoWindow`] whose text says
//!   why: no `DISPLAY`/`WAYLAND_DISPLAY`, libxkbcommon (or its X11 part) missing at
//!   run time, the display refusing the connection, or a build without the `window`
//!   feature. X11 and Wayland libraries are loaded at run time (dlopen), never linked.
//!
//! winit wants one event loop per process, and a C program's library cannot own the
//! main thread, so the loop runs on a thread of its own (winit's `with_any_thread`),
//! started by the first [`Window::open`] and kept for the process: later sessions
//! reuse it. Closing the window (its close button) ends the session's window, not the
//! loop.
//!
//! `VOODOO_WINDOW_CAPTURE=FILE` makes the window write the first frame it presents,
//! exactly the pixels handed to the display, to `FILE` as a binary PPM (P6), and then
//! send [`Event::Captured`]: the Xvfb test of `voodoo demo` compares it with the PNG.

use std::fmt;

/// A frame to show: `pixels` holds `width * height` values 0x00RRGGBB, row-major.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<u32>,
}

impl Frame {
    /// A frame from RGB565 pixels (`width * height` of them, row-major; missing ones
    /// black, extra ones ignored), each channel widened by bit replication.
    pub fn from_rgb565(width: usize, height: usize, rgb565: &[u16]) -> Self {
        let n = width.saturating_mul(height);
        let mut pixels: Vec<u32> = rgb565.iter().take(n).map(|&p| xrgb(p)).collect();
        pixels.resize(n, 0);
        Self {
            width,
            height,
            pixels,
        }
    }

    /// Fills `out`, `w * h` pixels, with the frame scaled to that size (nearest
    /// pixel); pixels missing from the frame are black.
    pub fn scale_into(&self, w: usize, h: usize, out: &mut [u32]) {
        if w == 0 || h == 0 {
            return;
        }
        let columns: Vec<usize> = (0..w).map(|x| x * self.width / w).collect();
        for (y, row) in out.chunks_exact_mut(w).take(h).enumerate() {
            let start = y * self.height / h * self.width;
            for (dst, &x) in row.iter_mut().zip(&columns) {
                *dst = self.pixels.get(start + x).copied().unwrap_or(0);
            }
        }
    }

    /// The frame as a binary PPM (P6): what `VOODOO_WINDOW_CAPTURE` writes.
    pub fn to_ppm(&self) -> Vec<u8> {
        let mut out = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
        for p in &self.pixels {
            out.extend_from_slice(&p.to_be_bytes()[1..]);
        }
        out
    }
}

/// An RGB565 pixel as 0x00RRGGBB, each channel widened by bit replication (the top
/// bits repeated into the new low bits, so 0 stays 0 and full stays 0xff).
pub fn xrgb(pixel: u16) -> u32 {
    let r = u32::from(pixel >> 11) & 0x1f;
    let g = u32::from(pixel >> 5) & 0x3f;
    let b = u32::from(pixel) & 0x1f;
    let (r, g, b) = (
        (r << 3) | (r >> 2),
        (g << 2) | (g >> 4),
        (b << 3) | (b >> 2),
    );
    (r << 16) | (g << 8) | b
}

/// A key pressed in the window.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Key {
    /// A key that types a character (as the keyboard layout gives it).
    Char(char),
    Left,
    Right,
    Up,
    Down,
    PageUp,
    PageDown,
    Home,
    End,
    Space,
    Enter,
    Tab,
    Escape,
}

/// What the window tells its session.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Event {
    /// A key was pressed (or repeats while held).
    Key(Key),
    /// The user closed the window.
    Closed,
    /// `VOODOO_WINDOW_CAPTURE` has been written (or could not be: the text says why).
    Captured(Result<(), String>),
}

/// Why no window opened, in words for the user.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NoWindow(pub String);

impl fmt::Display for NoWindow {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for NoWindow {}

/// Whether the environment names a display: `Err` with the reason when neither
/// `DISPLAY` nor `WAYLAND_DISPLAY` (or `WAYLAND_SOCKET`) is set and non-empty.
/// `Ok(true)` for Wayland, `Ok(false)` for X11.
pub fn display_from_env(
    var: impl Fn(&str) -> Option<std::ffi::OsString>,
) -> Result<bool, NoWindow> {
    let set = |k: &str| var(k).is_some_and(|v| !v.is_empty());
    if set("WAYLAND_DISPLAY") || set("WAYLAND_SOCKET") {
        Ok(true)
    } else if set("DISPLAY") {
        Ok(false)
    } else {
        Err(NoWindow(
            "no display is available (DISPLAY and WAYLAND_DISPLAY are unset)".into(),
        ))
    }
}

pub mod text;

#[cfg(feature = "window")]
mod live;
#[cfg(feature = "window")]
pub use live::Window;

#[cfg(not(feature = "window"))]
mod headless;
#[cfg(not(feature = "window"))]
pub use headless::Window;

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::OsString;

    #[test]
    fn xrgb_replicates_the_high_bits() {
        assert_eq!(xrgb(0xffff), 0x00ff_ffff);
        assert_eq!(xrgb(0x0000), 0);
        assert_eq!(xrgb(0xf800), 0x00ff_0000);
        assert_eq!(xrgb(0x07e0), 0x0000_ff00);
        assert_eq!(xrgb(0x001f), 0x0000_00ff);
        // r = 0b10000 -> 0b10000100, g = 0b100000 -> 0b10000010, b = 1 -> 0b00001000.
        assert_eq!(xrgb(0x8401), 0x0084_8208);
    }

    #[test]
    fn scale_doubles_and_halves_by_nearest_pixel() {
        let frame = Frame::from_rgb565(2, 2, &[0xf800, 0x07e0, 0x001f, 0xffff]);
        let (r, g, b, w) = (0x00ff_0000, 0x0000_ff00, 0x0000_00ff, 0x00ff_ffff);
        let mut out = vec![7; 16];
        frame.scale_into(4, 4, &mut out);
        assert_eq!(
            out,
            [r, r, g, g, r, r, g, g, b, b, w, w, b, b, w, w].to_vec()
        );
        let mut one = vec![7; 1];
        frame.scale_into(1, 1, &mut one);
        assert_eq!(one, [r]);
        let mut wide = vec![7; 3];
        frame.scale_into(3, 1, &mut wide);
        assert_eq!(wide, [r, r, g]);
    }

    #[test]
    fn missing_pixels_are_black() {
        let frame = Frame::from_rgb565(2, 2, &[0xffff]);
        assert_eq!(frame.pixels, [0x00ff_ffff, 0, 0, 0]);
        let mut out = vec![7; 4];
        frame.scale_into(0, 2, &mut out);
        assert_eq!(out, [7; 4]);
    }

    #[test]
    fn ppm_is_p6_rgb() {
        let frame = Frame::from_rgb565(2, 1, &[0xf800, 0x001f]);
        assert_eq!(frame.to_ppm(), b"P6\n2 1\n255\n\xff\0\0\0\0\xff".to_vec());
    }

    #[test]
    fn display_comes_from_the_environment() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| {
                pairs
                    .iter()
                    .find(|(n, _)| *n == k)
                    .map(|(_, v)| OsString::from(v))
            }
        };
        assert_eq!(display_from_env(env(&[("DISPLAY", ":0")])), Ok(false));
        assert_eq!(
            display_from_env(env(&[("DISPLAY", ":0"), ("WAYLAND_DISPLAY", "wayland-0")])),
            Ok(true)
        );
        let none = display_from_env(env(&[("DISPLAY", "")])).unwrap_err();
        assert_eq!(
            none.0,
            "no display is available (DISPLAY and WAYLAND_DISPLAY are unset)"
        );
        assert!(display_from_env(env(&[])).is_err());
    }
}
