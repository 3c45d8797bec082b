//! The window thread (winit event loop, softbuffer surface) and a session's handle.

use crate::{Event, Frame, Key, NoWindow};
use softbuffer::{Context, Surface};
use std::num::NonZeroU32;
use std::panic::{self, AssertUnwindSafe};
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::mpsc::{self, Receiver, Sender, SyncSender};
use std::sync::{Arc, Mutex, OnceLock, PoisonError};
use std::time::Duration;
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, WindowEvent};
use winit::event_loop::{ActiveEventLoop, EventLoop, EventLoopProxy};
use winit::keyboard::{Key as WinitKey, NamedKey};
// The x11 and wayland `with_any_thread` set the same flag of the builder.
use winit::platform::x11::EventLoopBuilderExtX11;
use winit::window::{Window as WinitWindow, WindowId};

/// The newest frame the window has not taken yet, and the session that showed it.
type Slot = Arc<Mutex<Option<(u64, Frame)>>>;

/// The number of the next session (sessions are told apart by it, so a session that
/// ends after a newer one began cannot close the newer one's window).
static NEXT_SESSION: AtomicU64 = AtomicU64::new(1);

/// What a session tells the window thread.
enum Msg {
    /// A new session: its number, title and where its events go. Ends any earlier one.
    Open {
        id: u64,
        title: String,
        events: Sender<Event>,
    },
    /// A new frame is in the slot.
    Frame,
    /// A new title for the session's window.
    Title(u64, String),
    /// The session ended: close its window.
    Close(u64),
}

/// The sessions' side of the window thread, one per process.
struct Viewer {
    proxy: EventLoopProxy<Msg>,
    slot: Slot,
}

/// The window thread, or why it could not start (the same for the whole process).
static VIEWER: OnceLock<Result<Viewer, NoWindow>> = OnceLock::new();

/// How long the first [`Window::open`] waits for the window thread to reach the display.
const START_TIMEOUT: Duration = Duration::from_secs(5);

/// One session of the window: open from [`Window::open`] until dropped.
pub struct Window {
    id: u64,
    viewer: &'static Viewer,
    events: Mutex<Receiver<Event>>,
}

impl std::fmt::Debug for Window {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Window")
    }
}

impl Window {
    /// Starts a session titled `title`; its window opens with the first frame shown,
    /// at that frame's size. `Err` says why no window can open (the first call's
    /// reason holds for the whole process).
    pub fn open(title: &str) -> Result<Self, NoWindow> {
        let viewer = VIEWER.get_or_init(start).as_ref().map_err(Clone::clone)?;
        let (tx, rx) = mpsc::channel();
        let id = NEXT_SESSION.fetch_add(1, Ordering::Relaxed);
        viewer
            .proxy
            .send_event(Msg::Open {
                id,
                title: title.to_string(),
                events: tx,
            })
            .map_err(|_| NoWindow("the window thread has stopped".into()))?;
        Ok(Self {
            id,
            viewer,
            events: Mutex::new(rx),
        })
    }

    /// Shows `frame` (replacing one the window has not taken yet); never waits.
    pub fn show(&self, frame: Frame) {
        *self
            .viewer
            .slot
            .lock()
            .unwrap_or_else(PoisonError::into_inner) = Some((self.id, frame));
        // An error means the window thread stopped: the caller goes on without it.
        let _ = self.viewer.proxy.send_event(Msg::Frame);
    }

    /// Sets the window's title.
    pub fn set_title(&self, title: &str) {
        let _ = self
            .viewer
            .proxy
            .send_event(Msg::Title(self.id, title.to_string()));
    }

    /// Waits for the next key press, the window's closing or its capture; `None` when
    /// the window thread has stopped (no more events will come).
    pub fn next_event(&self) -> Option<Event> {
        self.events
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .recv()
            .ok()
    }
}

impl Window {
    /// The next event if one is waiting, without waiting.
    pub fn try_event(&self) -> Option<Event> {
        self.events
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .try_recv()
            .ok()
    }
}

impl Drop for Window {
    fn drop(&mut self) {
        let _ = self.viewer.proxy.send_event(Msg::Close(self.id));
    }
}

/// Starts the window thread and waits until its event loop holds the display.
fn start() -> Result<Viewer, NoWindow> {
    let wayland = crate::display_from_env(|k| std::env::var_os(k))?;
    // winit 0.30 panics when it cannot load these (it picks Wayland as we do here).
    if xkbcommon_dl::xkbcommon_option().is_none() {
        return Err(NoWindow(
            "libxkbcommon cannot be loaded (Debian: libxkbcommon0)".into(),
        ));
    }
    if !wayland && xkbcommon_dl::x11::xkbcommon_x11_option().is_none() {
        return Err(NoWindow(
            "libxkbcommon-x11 cannot be loaded (Debian: libxkbcommon-x11-0)".into(),
        ));
    }
    let capture = std::env::var_os("VOODOO_WINDOW_CAPTURE")
        .filter(|v| !v.is_empty())
        .map(PathBuf::from);
    let slot = Slot::default();
    let app_slot = slot.clone();
    let (tx, rx) = mpsc::sync_channel(1);
    std::thread::Builder::new()
        .name("sst1-window".into())
        .spawn(move || {
            // Should winit panic all the same, the program goes on without a window.
            let run = panic::catch_unwind(AssertUnwindSafe(|| run_window(&tx, app_slot, capture)));
            if let Err(payload) = run {
                let why = payload
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| payload.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "winit panicked".into());
                // Before the loop ran, `start` reports it; after, this thread.
                if tx.send(Err(why.clone())).is_err() {
                    eprintln!("the window stopped ({why})");
                }
            }
        })
        .map_err(|e| NoWindow(format!("the window thread cannot start ({e})")))?;
    match rx.recv_timeout(START_TIMEOUT) {
        Ok(Ok(proxy)) => Ok(Viewer { proxy, slot }),
        Ok(Err(e)) => Err(NoWindow(format!("no window can be opened ({e})"))),
        Err(_) => Err(NoWindow("the display did not answer".into())),
    }
}

/// The window thread's work: builds the event loop, hands its proxy (or why it cannot
/// be built) to `start`, and runs it for the rest of the process.
fn run_window(
    started: &SyncSender<Result<EventLoopProxy<Msg>, String>>,
    slot: Slot,
    capture: Option<PathBuf>,
) {
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
        session: None,
        frame: None,
        view: None,
        capture,
    };
    if let Err(e) = event_loop.run_app(&mut app) {
        eprintln!("the window stopped ({})", reason(&e));
    }
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

/// The key a winit key press means to us, if any.
fn key(logical: &WinitKey) -> Option<Key> {
    Some(match logical {
        WinitKey::Named(named) => match named {
            NamedKey::ArrowLeft => Key::Left,
            NamedKey::ArrowRight => Key::Right,
            NamedKey::ArrowUp => Key::Up,
            NamedKey::ArrowDown => Key::Down,
            NamedKey::PageUp => Key::PageUp,
            NamedKey::PageDown => Key::PageDown,
            NamedKey::Home => Key::Home,
            NamedKey::End => Key::End,
            NamedKey::Space => Key::Space,
            NamedKey::Enter => Key::Enter,
            NamedKey::Tab => Key::Tab,
            NamedKey::Escape => Key::Escape,
            _ => return None,
        },
        WinitKey::Character(text) => {
            let mut chars = text.chars();
            match (chars.next(), chars.next()) {
                (Some(' '), None) => Key::Space,
                (Some(c), None) => Key::Char(c),
                _ => return None,
            }
        }
        _ => return None,
    })
}

/// An open window and the surface its pixels go to.
struct View {
    window: Rc<WinitWindow>,
    surface: Surface<Rc<WinitWindow>, Rc<WinitWindow>>,
}

impl View {
    /// Opens a window of the frame's size (physical pixels, so 1:1 with the frame).
    fn open(event_loop: &ActiveEventLoop, title: &str, frame: &Frame) -> Result<Self, String> {
        let attributes = WinitWindow::default_attributes()
            .with_title(title)
            .with_inner_size(PhysicalSize::new(
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

    /// Draws `frame` scaled to the window's size; returns what was presented (width,
    /// height, pixels) when `keep` asks for it.
    fn draw(
        &mut self,
        frame: &Frame,
        keep: bool,
    ) -> Result<Option<Frame>, softbuffer::SoftBufferError> {
        let size = self.window.inner_size();
        let (Some(w), Some(h)) = (NonZeroU32::new(size.width), NonZeroU32::new(size.height)) else {
            return Ok(None); // minimised
        };
        self.surface.resize(w, h)?;
        let mut buffer = self.surface.buffer_mut()?;
        let (w, h) = (w.get() as usize, h.get() as usize);
        frame.scale_into(w, h, &mut buffer);
        let kept = keep.then(|| Frame {
            width: w,
            height: h,
            pixels: buffer.to_vec(),
        });
        buffer.present()?;
        Ok(kept)
    }
}

/// The session on show: its number, where its events go and its title.
struct Session {
    id: u64,
    events: Sender<Event>,
    title: String,
    /// The user closed its window: later frames of the session are not shown.
    closed: bool,
}

/// The window thread's state.
struct App {
    slot: Slot,
    session: Option<Session>,
    /// The frame on show, kept for redraws.
    frame: Option<Frame>,
    view: Option<View>,
    /// `VOODOO_WINDOW_CAPTURE`, until the first presented frame is written there.
    capture: Option<PathBuf>,
}

impl App {
    fn send(&self, event: Event) {
        if let Some(s) = &self.session {
            let _ = s.events.send(event);
        }
    }

    /// Closes the window (the session, if any, stays until it ends).
    fn close_view(&mut self) {
        self.view = None;
        self.frame = None;
    }

    /// Shows the newest frame, opening the window for the first one.
    fn new_frame(&mut self, event_loop: &ActiveEventLoop) {
        let Some((id, frame)) = self
            .slot
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .take()
        else {
            return; // already shown by an earlier wake-up
        };
        let Some(session) = &self.session else {
            return;
        };
        if session.closed || session.id != id {
            return;
        }
        if self.view.is_none() {
            match View::open(event_loop, &session.title, &frame) {
                Ok(view) => self.view = Some(view),
                Err(e) => {
                    eprintln!("cannot open a window ({e})");
                    if let Some(s) = &mut self.session {
                        s.closed = true;
                    }
                    self.send(Event::Closed);
                    return;
                }
            }
        }
        self.frame = Some(frame);
        if let Some(view) = &self.view {
            view.window.request_redraw();
        }
    }

    fn redraw(&mut self) {
        let (Some(view), Some(frame)) = (&mut self.view, &self.frame) else {
            return;
        };
        match view.draw(frame, self.capture.is_some()) {
            Ok(Some(shown)) => {
                if let Some(path) = self.capture.take() {
                    // Written whole under another name, then renamed: a program
                    // waiting for the file never sees half of it.
                    let mut part = path.clone().into_os_string();
                    part.push(".part");
                    let written = std::fs::write(&part, shown.to_ppm())
                        .and_then(|()| std::fs::rename(&part, &path))
                        .map_err(|e| format!("{}: {e}", path.display()));
                    self.send(Event::Captured(written));
                }
            }
            Ok(None) => {}
            Err(e) => {
                eprintln!("the window cannot draw ({e})");
                self.close_view();
                if let Some(s) = &mut self.session {
                    s.closed = true;
                }
                self.send(Event::Closed);
            }
        }
    }
}

impl ApplicationHandler<Msg> for App {
    fn resumed(&mut self, _event_loop: &ActiveEventLoop) {
        // A session's window opens with its first frame, whose size it takes.
    }

    fn user_event(&mut self, event_loop: &ActiveEventLoop, msg: Msg) {
        match msg {
            Msg::Open { id, title, events } => {
                self.close_view();
                self.session = Some(Session {
                    id,
                    events,
                    title,
                    closed: false,
                });
            }
            Msg::Frame => self.new_frame(event_loop),
            Msg::Title(id, title) => {
                if let Some(s) = self.session.as_mut().filter(|s| s.id == id) {
                    if let Some(view) = &self.view {
                        view.window.set_title(&title);
                    }
                    s.title = title;
                }
            }
            Msg::Close(id) => {
                if self.session.as_ref().is_some_and(|s| s.id == id) {
                    self.close_view();
                    self.session = None;
                }
            }
        }
    }

    fn window_event(&mut self, _event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => {
                self.close_view();
                if let Some(s) = &mut self.session {
                    s.closed = true;
                }
                self.send(Event::Closed);
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                if let Some(k) = key(&event.logical_key) {
                    self.send(Event::Key(k));
                }
            }
            WindowEvent::Resized(_) => {
                if let Some(view) = &self.view {
                    view.window.request_redraw();
                }
            }
            WindowEvent::RedrawRequested => self.redraw(),
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reason_drops_the_winit_source_location() {
        assert_eq!(
            reason(&"os error at /x/winit/src/mod.rs:788: Failed to open connection"),
            "Failed to open connection"
        );
        assert_eq!(reason(&"no backend: x: y"), "no backend: x: y");
    }

    #[test]
    fn keys_map_by_name_and_character() {
        assert_eq!(key(&WinitKey::Named(NamedKey::ArrowLeft)), Some(Key::Left));
        assert_eq!(key(&WinitKey::Named(NamedKey::Escape)), Some(Key::Escape));
        assert_eq!(key(&WinitKey::Character("f".into())), Some(Key::Char('f')));
        assert_eq!(key(&WinitKey::Character(" ".into())), Some(Key::Space));
        assert_eq!(key(&WinitKey::Character("ab".into())), None);
        assert_eq!(key(&WinitKey::Named(NamedKey::Shift)), None);
    }
}
