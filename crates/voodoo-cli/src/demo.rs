//! `voodoo demo`: the demo scene (`glide::demo`) drawn live through the Glide 3
//! front-end on an emulated two-TMU board.

use glide::BoardInfo;
use sst1_board::{Board, BoardConfig, BufferKind};
use std::cell::RefCell;
use std::rc::Rc;

/// The board the demo runs on: two TMUs (the light map is on the second).
pub fn config() -> BoardConfig {
    BoardConfig {
        tmus: glide::demo::TMUS,
        ..BoardConfig::default()
    }
}

/// The displayed picture: width, height and RGB565 pixels, row-major.
pub struct Picture {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u16>,
}

/// Draws the demo on `board` (fresh, of [`config`]) and swaps it to the front: opens
/// Glide at 640x480, draws `glide::demo::draw`, `grBufferSwap(1)`. A Glide error (there
/// should be none) is returned as text.
pub fn render_on(board: Board) -> Result<Picture, String> {
    let shared = Rc::new(RefCell::new(board));
    let info = BoardInfo::new(config().fbi_mb, config().tmus, config().tmu_mb);
    glide::demo::render(Box::new(shared.clone()), info)?;
    let board = shared.borrow();
    let (width, height) = board.display_size();
    Ok(Picture {
        width,
        height,
        pixels: board.dump_buffer(BufferKind::Front),
    })
}

/// Shows `picture` in a window until the user closes it or presses Escape or Q (or,
/// with `VOODOO_WINDOW_CAPTURE`, until the window has written what it presented).
/// Where no window opens, one line on stderr says why and where the PNG is; `Err` only
/// when the capture cannot be written.
pub fn show(picture: &Picture, png: &std::path::Path) -> Result<(), String> {
    use sst1_window::{Event, Frame, Key, Window};
    let window = match Window::open("voodoo demo (Esc or Q: quit)") {
        Ok(window) => window,
        Err(why) => {
            eprintln!(
                "voodoo: no window: {why}; the picture is in {}",
                png.display()
            );
            return Ok(());
        }
    };
    window.show(Frame::from_rgb565(
        picture.width as usize,
        picture.height as usize,
        &picture.pixels,
    ));
    loop {
        match window.next_event() {
            Some(Event::Key(Key::Escape | Key::Char('q' | 'Q')))
            | Some(Event::Closed)
            | Some(Event::Captured(Ok(())))
            | None => return Ok(()),
            Some(Event::Captured(Err(e))) => return Err(format!("VOODOO_WINDOW_CAPTURE: {e}")),
            Some(Event::Key(_)) => {}
        }
    }
}
