//! The live window of `VOODOO_WINDOW=1`: what the monitor of the board would show.
//!
//! After every buffer swap (spec 5.24 swapbufferCMD) the front buffer, of the size the
//! video timing gives (spec 5.41 videoDimensions), goes to a window, its RGB565 pixels
//! expanded to 8 bits a channel by bit replication and scaled (nearest pixel) to the
//! window's size. Headless is the default: the window needs the cargo feature `window`
//! (winit + softbuffer, X11 or Wayland) and a display; without either, one line on
//! stderr says so and the program goes on headless.
//!
//! A C program's library cannot own the main thread, where winit wants its event loop
//! by default, so the loop runs on a thread of its own (winit's `with_any_thread`),
//! started once per process (winit builds one event loop per process). The program's
//! thread never waits on the window: a swap puts the frame in a one-frame slot,
//! replacing any frame the window has not taken yet, and wakes the loop.
//! `grGlideShutdown` closes the window; closing the window ends the loop, and the
//! program goes on headless; the program's exit ends the thread.

/// Whether a `VOODOO_WINDOW` value asks for a window: set, non-empty and not `0`.
fn requested(value: Option<&std::ffi::OsStr>) -> bool {
    value.is_some_and(|v| !v.is_empty() && v != "0")
}

#[cfg(not(feature = "window"))]
pub(crate) use headless::LiveWindow;
#[cfg(feature = "window")]
pub(crate) use live::LiveWindow;

#[cfg(all(
    feature = "window",
    not(any(
        target_os = "linux",
        target_os = "freebsd",
        target_os = "dragonfly",
        target_os = "netbsd",
        target_os = "openbsd"
    ))
))]
compile_error!("the `window` feature of glide3-c needs X11 or Wayland (Linux or a BSD)");

/// This build has no window: `VOODOO_WINDOW` gets one line on stderr.
#[cfg(not(feature = "window"))]
mod headless {
    use sst1_board::Board;

    /// A live window, which this build cannot open: the type has no values.
    pub(crate) enum LiveWindow {}

    impl LiveWindow {
        /// Says once per process on stderr why `VOODOO_WINDOW` gets no window.
        pub(crate) fn from_env() -> Option<Self> {
            static WARNED: std::sync::Once = std::sync::Once::new();
            if super::requested(std::env::var_os("VOODOO_WINDOW").as_deref()) {
                WARNED.call_once(|| {
                    eprintln!(
                        "glide3: VOODOO_WINDOW is set, but this libglide3 was built without \
                         the `window` feature (cargo build --release -p glide3-c --features \
                         window); running headless"
                    )
                });
            }
            None
        }

        /// Never called: there is no window.
        pub(crate) fn show(&self, _board: &Board) {
            match *self {}
        }
    }
}

/// The window thread (winit event loop, softbuffer surface) and the program's handle.
#[cfg(feature = "window")]
mod live {
    use softbuffer::{Context, Surface};
    use sst1_board::{Board, BufferKind};
    use sst1_trace::rgb565_to_rgb8;
    use std::num::NonZeroU32;
    use std::panic::{self, AssertUnwindSafe};
    use std::rc::Rc;
    use std::sync::mpsc::{self, SyncSender};
    use std::sync::{Arc, Mutex, OnceLock, PoisonError};
    use std::time::Duration;
    use winit::application::ApplicationHandler;
    use winit::dpi::LogicalSize;
    use winit::event::WindowEvent;
    use winit::event_loop::{ActiveEventLoop, EventLoop, EventLoopProxy};
    // The x11 and wayland `with_any_thread` set the same flag of the builder.
    use winit::platform::x11::EventLoopBuilderExtX11;
    use winit::window::{Window, WindowId};

    /// The newest frame the window has not taken yet.
    type Slot = Arc<Mutex<Option<Frame>>>;

    /// What the program's thread tells the window thread.
    enum Msg {
        /// A new frame is in the slot.
        Frame,
        /// `grGlideShutdown`: close the window (a later session may open another).
        Close,
    }

    /// The program's side of the window thread, one per process.
    struct Viewer {
        proxy: EventLoopProxy<Msg>,
        slot: Slot,
    }

    /// The window thread, or `None` when it could not start (said once on stderr).
    static VIEWER: OnceLock<Option<Viewer>> = OnceLock::new();

    /// How long `grGlideInit` waits for the window thread to reach the display.
    const START_TIMEOUT: Duration = Duration::from_secs(5);

    /// The live window of one Glide session (`grGlideInit` to `grGlideShutdown`).
    pub(crate) struct LiveWindow {
        viewer: &'static Viewer,
    }

    impl LiveWindow {
        /// Starts the window thread when `VOODOO_WINDOW` asks for it; `None` when it is
        /// not asked for, or cannot start (the reason goes to stderr once per process).
        pub(crate) fn from_env() -> Option<Self> {
            if !super::requested(std::env::var_os("VOODOO_WINDOW").as_deref()) {
                return None;
            }
            let viewer = VIEWER.get_or_init(|| match start() {
                Ok(viewer) => Some(viewer),
                Err(why) => {
                    eprintln!("glide3: VOODOO_WINDOW is set, but {why}; running headless");
                    None
                }
            });
            Some(Self {
                viewer: viewer.as_ref()?,
            })
        }

        /// Hands the front buffer to the window (after a buffer swap).
        pub(crate) fn show(&self, board: &Board) {
            let (width, height) = board.display_size();
            let frame = Frame {
                width: width as usize,
                height: height as usize,
                pixels: board.dump_buffer(BufferKind::Front),
            };
            *self
                .viewer
                .slot
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = Some(frame);
            // An error means the user closed the window: the program goes on headless.
            let _ = self.viewer.proxy.send_event(Msg::Frame);
        }
    }

    impl Drop for LiveWindow {
        fn drop(&mut self) {
            let _ = self.viewer.proxy.send_event(Msg::Close);
        }
    }

    /// Starts the window thread and waits until its event loop holds the display.
    fn start() -> Result<Viewer, String> {
        let set = |k: &str| std::env::var_os(k).is_some_and(|v| !v.is_empty());
        let wayland = set("WAYLAND_DISPLAY") || set("WAYLAND_SOCKET");
        if !wayland && !set("DISPLAY") {
            return Err("no display is available (DISPLAY and WAYLAND_DISPLAY are unset)".into());
        }
        // winit 0.30 panics when it cannot load these (it picks Wayland as we do here).
        if xkbcommon_dl::xkbcommon_option().is_none() {
            return Err("libxkbcommon cannot be loaded (Debian: libxkbcommon0)".into());
        }
        if !wayland && xkbcommon_dl::x11::xkbcommon_x11_option().is_none() {
            return Err("libxkbcommon-x11 cannot be loaded (Debian: libxkbcommon-x11-0)".into());
        }
        let slot = Slot::default();
        let app_slot = slot.clone();
        let (tx, rx) = mpsc::sync_channel(1);
        std::thread::Builder::new()
            .name("glide3-window".into())
            .spawn(move || {
                // Should winit panic all the same, the program goes on headless.
                let run = panic::catch_unwind(AssertUnwindSafe(|| run_window(&tx, app_slot)));
                if let Err(payload) = run {
                    let why = payload
                        .downcast_ref::<&str>()
                        .map(|s| s.to_string())
                        .or_else(|| payload.downcast_ref::<String>().cloned())
                        .unwrap_or_else(|| "winit panicked".into());
                    // Before the loop ran, grGlideInit reports it; after, this thread.
                    if tx.send(Err(why.clone())).is_err() {
                        eprintln!("glide3: the window stopped ({why}); running headless");
                    }
                }
            })
            .map_err(|e| format!("the window thread cannot start ({e})"))?;
        match rx.recv_timeout(START_TIMEOUT) {
            Ok(Ok(proxy)) => Ok(Viewer { proxy, slot }),
            Ok(Err(e)) => Err(format!("no window can be opened ({e})")),
            Err(_) => Err("the display did not answer".into()),
        }
    }

    /// The window thread's work: builds the event loop, hands its proxy (or why it
    /// cannot be built) to `start`, and runs it until the user closes the window.
    fn run_window(started: &SyncSender<Result<EventLoopProxy<Msg>, String>>, slot: Slot) {
        let event_loop = match EventLoop::<Msg>::with_user_event()
            .with_any_thread(true)
            .build()
        {
            Ok(event_loop) => event_loop,
            Err(e) => {
                let _ = started.send(Err(reason(&e)));
                return;
            }
        };
        let _ = started.send(Ok(event_loop.create_proxy()));
        let mut app = App {
            slot,
            frame: None,
            view: None,
        };
        if let Err(e) = event_loop.run_app(&mut app) {
            eprintln!(
                "glide3: the window stopped ({}); running headless",
                reason(&e)
            );
        }
    }

    /// One displayed frame: RGB565 pixels, row-major, `width * height` of them.
    struct Frame {
        width: usize,
        height: usize,
        pixels: Vec<u16>,
    }

    impl Frame {
        /// Fills `out`, `w * h` pixels in softbuffer's 0x00RRGGBB, with the frame scaled
        /// to that size (nearest pixel); pixels missing from the frame are black.
        fn scale_into(&self, w: usize, h: usize, out: &mut [u32]) {
            if w == 0 || h == 0 {
                return;
            }
            let columns: Vec<usize> = (0..w).map(|x| x * self.width / w).collect();
            for (y, row) in out.chunks_exact_mut(w).take(h).enumerate() {
                let start = y * self.height / h * self.width;
                for (dst, &x) in row.iter_mut().zip(&columns) {
                    *dst = self.pixels.get(start + x).map_or(0, |&p| xrgb(p));
                }
            }
        }
    }

    /// An RGB565 pixel as 0x00RRGGBB, each channel widened by bit replication.
    fn xrgb(pixel: u16) -> u32 {
        let [r, g, b] = rgb565_to_rgb8(pixel);
        u32::from_be_bytes([0, r, g, b])
    }

    /// winit's error text without the `os error at FILE:LINE: ` naming winit's own source.
    fn reason(error: &dyn std::fmt::Display) -> String {
        let text = error.to_string();
        match text
            .strip_prefix("os error at ")
            .and_then(|rest| rest.split_once(": "))
        {
            Some((_, why)) => why.to_string(),
            None => text,
        }
    }

    /// An open window and the surface its pixels go to.
    struct View {
        window: Rc<Window>,
        surface: Surface<Rc<Window>, Rc<Window>>,
    }

    impl View {
        /// Opens a window of the frame's size (logical pixels).
        fn open(event_loop: &ActiveEventLoop, frame: &Frame) -> Result<Self, String> {
            let attributes = Window::default_attributes()
                .with_title("Voodoo Graphics (libglide3)")
                .with_inner_size(LogicalSize::new(
                    frame.width.max(1) as u32,
                    frame.height.max(1) as u32,
                ));
            let window = Rc::new(
                event_loop
                    .create_window(attributes)
                    .map_err(|e| reason(&e))?,
            );
            let context = Context::new(window.clone()).map_err(|e| e.to_string())?;
            let surface = Surface::new(&context, window.clone()).map_err(|e| e.to_string())?;
            Ok(Self { window, surface })
        }

        /// Draws `frame` scaled to the window's size.
        fn draw(&mut self, frame: &Frame) -> Result<(), softbuffer::SoftBufferError> {
            let size = self.window.inner_size();
            let (Some(w), Some(h)) = (NonZeroU32::new(size.width), NonZeroU32::new(size.height))
            else {
                return Ok(()); // minimised
            };
            self.surface.resize(w, h)?;
            let mut buffer = self.surface.buffer_mut()?;
            frame.scale_into(w.get() as usize, h.get() as usize, &mut buffer);
            buffer.present()
        }
    }

    /// The window thread's state.
    struct App {
        slot: Slot,
        /// The frame on show, kept for redraws.
        frame: Option<Frame>,
        view: Option<View>,
    }

    impl App {
        /// Shows the newest frame, opening the window for the first one.
        fn new_frame(&mut self, event_loop: &ActiveEventLoop) {
            let Some(frame) = self
                .slot
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .take()
            else {
                return; // already shown by an earlier wake-up
            };
            if self.view.is_none() {
                match View::open(event_loop, &frame) {
                    Ok(view) => self.view = Some(view),
                    Err(e) => {
                        eprintln!("glide3: cannot open a window ({e}); running headless");
                        event_loop.exit();
                        return;
                    }
                }
            }
            self.frame = Some(frame);
            if let Some(view) = &self.view {
                view.window.request_redraw();
            }
        }
    }

    impl ApplicationHandler<Msg> for App {
        fn resumed(&mut self, _event_loop: &ActiveEventLoop) {
            // The window opens with the first frame, whose size it takes.
        }

        fn user_event(&mut self, event_loop: &ActiveEventLoop, msg: Msg) {
            match msg {
                Msg::Frame => self.new_frame(event_loop),
                Msg::Close => {
                    self.view = None;
                    self.frame = None;
                }
            }
        }

        fn window_event(
            &mut self,
            event_loop: &ActiveEventLoop,
            _id: WindowId,
            event: WindowEvent,
        ) {
            match event {
                WindowEvent::CloseRequested => {
                    self.view = None;
                    event_loop.exit();
                }
                WindowEvent::Resized(_) => {
                    if let Some(view) = &self.view {
                        view.window.request_redraw();
                    }
                }
                WindowEvent::RedrawRequested => {
                    if let (Some(view), Some(frame)) = (&mut self.view, &self.frame) {
                        if let Err(e) = view.draw(frame) {
                            eprintln!("glide3: the window cannot draw ({e}); running headless");
                            self.view = None;
                            event_loop.exit();
                        }
                    }
                }
                _ => {}
            }
        }
    }

    #[cfg(test)]
    mod tests {
        use super::*;

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
            let frame = Frame {
                width: 2,
                height: 2,
                pixels: vec![0xf800, 0x07e0, 0x001f, 0xffff],
            };
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
        fn reason_drops_the_winit_source_location() {
            assert_eq!(
                reason(&"os error at /x/winit/src/mod.rs:788: Failed to open connection"),
                "Failed to open connection"
            );
            assert_eq!(reason(&"no backend: x: y"), "no backend: x: y");
        }

        #[test]
        fn scale_fills_missing_pixels_with_black() {
            let frame = Frame {
                width: 2,
                height: 2,
                pixels: vec![0xffff],
            };
            let mut out = vec![7; 4];
            frame.scale_into(2, 2, &mut out);
            assert_eq!(out, [0x00ff_ffff, 0, 0, 0]);
            frame.scale_into(0, 2, &mut out);
            assert_eq!(out, [0x00ff_ffff, 0, 0, 0]);
        }
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
