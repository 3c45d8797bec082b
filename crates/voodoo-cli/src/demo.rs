//! `voodoo demo`: the demo scene (`glide::demo`) drawn live through the Glide 3
//! front-end on an emulated two-TMU board.

use glide::consts::*;
use glide::{BoardInfo, Glide, RegisterBus};
use sst1_board::{Board, BoardConfig, BufferKind};
use std::cell::RefCell;
use std::rc::Rc;

/// The board, shared by the Glide context (which writes it) and the caller (which
/// reads the picture back).
#[derive(Clone)]
struct SharedBoard(Rc<RefCell<Board>>);

impl RegisterBus for SharedBoard {
    fn write32(&mut self, addr: u32, value: u32) {
        self.0.borrow_mut().write32(addr, value);
    }
    fn read32(&mut self, addr: u32) -> u32 {
        self.0.borrow_mut().read32(addr)
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        self.0.borrow_mut().pci_write(offset, value);
    }
    fn host_wait(&mut self, cycles: u64) {
        self.0.borrow_mut().host_wait(cycles);
    }
}

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
    let shared = SharedBoard(Rc::new(RefCell::new(board)));
    let info = BoardInfo::new(config().fbi_mb, config().tmus, config().tmu_mb);
    let mut g = Glide::init(Box::new(shared.clone()), info);
    g.sst_select(0);
    if !g.win_open(
        GR_RESOLUTION_640x480,
        GR_REFRESH_60Hz,
        GR_COLORFORMAT_ARGB,
        GR_ORIGIN_UPPER_LEFT,
        2,
        1,
    ) {
        return Err(format!(
            "the demo cannot open Glide at 640x480: {}",
            g.last_error().unwrap_or("grSstWinOpen failed")
        ));
    }
    glide::demo::draw(&mut g);
    g.buffer_swap(1);
    if let Some(e) = g.last_error() {
        return Err(format!("the demo scene made a Glide error: {e}"));
    }
    drop(g.shutdown());
    let board = shared.0.borrow();
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
