//! The live window of `VOODOO_WINDOW=1`: what the monitor of the board would show.
//!
//! After every buffer swap (spec 5.24 swapbufferCMD) the front buffer, of the size the
//! video timing gives (spec 5.41 videoDimensions), goes to a window (`sst1-window`:
//! RGB565 expanded to 8 bits a channel by bit replication, scaled to the window's size
//! by nearest pixel). Without `VOODOO_WINDOW` there is no window. Where the window
//! cannot open (no display, libxkbcommon missing at run time, a build without the
//! default feature `window`), one line on stderr says why, once per process, and the
//! program goes on headless.
//!
//! The program's thread never waits on the window: a swap replaces any frame the window
//! has not taken yet (`sst1_window::Window::show`). `grGlideShutdown` closes the
//! window; closing the window stops the session's frames, and the program goes on
//! headless. Key presses in the window are dropped.

use sst1_board::{Board, BufferKind};
use sst1_window::{Frame, Window};

/// Whether a `VOODOO_WINDOW` value asks for a window: set, non-empty and not `0`.
fn requested(value: Option<&std::ffi::OsStr>) -> bool {
    value.is_some_and(|v| !v.is_empty() && v != "0")
}

/// The live window of one Glide session (`grGlideInit` to `grGlideShutdown`).
pub(crate) struct LiveWindow(Window);

impl LiveWindow {
    /// Opens the window when `VOODOO_WINDOW` asks for it; `None` when it is not asked
    /// for, or cannot open (the reason goes to stderr once per process).
    pub(crate) fn from_env() -> Option<Self> {
        if !requested(std::env::var_os("VOODOO_WINDOW").as_deref()) {
            return None;
        }
        match Window::open("Voodoo Graphics (libglide3)") {
            Ok(window) => Some(Self(window)),
            Err(why) => {
                static WARNED: std::sync::Once = std::sync::Once::new();
                WARNED.call_once(|| {
                    eprintln!("glide3: VOODOO_WINDOW is set, but {why}; running headless")
                });
                None
            }
        }
    }

    /// Hands the front buffer to the window (after a buffer swap).
    pub(crate) fn show(&self, board: &Board) {
        // Key presses and the window's closing need no answer here: drop them.
        while self.0.try_event().is_some() {}
        let (width, height) = board.display_size();
        self.0.show(Frame::from_rgb565(
            width as usize,
            height as usize,
            &board.dump_buffer(BufferKind::Front),
        ));
    }
}

#[cfg(test)]
mod tests {
    use super::requested;
    use std::ffi::OsStr;

    #[test]
    fn voodoo_window_values() {
        assert!(requested(Some(OsStr::new("1"))));
        assert!(requested(Some(OsStr::new("yes"))));
        assert!(!requested(Some(OsStr::new("0"))));
        assert!(!requested(Some(OsStr::new(""))));
        assert!(!requested(None));
    }
}
