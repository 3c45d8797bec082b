//! The window shows what the PNG holds: `voodoo demo` and `voodoo play` under Xvfb, with
//! `VOODOO_WINDOW_CAPTURE` making the window write the first frame it presented (the
//! pixels handed to the display), compared with the PNG of the same picture.
//!
//! Needs `Xvfb` on the PATH (Debian: `apt-get install xvfb`) and libxkbcommon-x11 at run
//! time; where either is missing, each test says so on stderr and passes without
//! checking.

#[path = "../../sst1-window/tests/support/xvfb.rs"]
mod xvfb;

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use xvfb::Server;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("voodoo-window-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `voodoo ARGS` on `server`'s display with the capture on; `None` (said on
/// stderr) where the window could not open. Kills a run that has not ended after two
/// minutes (a safety net against a hang, not a measurement).
fn run_captured(test: &str, server: &Server, dir: &Path, args: &[&str]) -> Option<Vec<u8>> {
    let capture = dir.join("capture.ppm");
    let mut child = Command::new(env!("CARGO_BIN_EXE_voodoo"))
        .args(args)
        .current_dir(dir)
        .env("DISPLAY", &server.display)
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env("VOODOO_WINDOW_CAPTURE", &capture)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut status = None;
    for _ in 0..1200 {
        if let Some(s) = child.try_wait().unwrap() {
            status = Some(s);
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
    let Some(status) = status else {
        let _ = child.kill();
        panic!("{test}: voodoo {args:?} did not end");
    };
    let mut stderr = String::new();
    use std::io::Read;
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    if let Some(why) = stderr.lines().find(|l| l.contains("no window")) {
        eprintln!("{test}: skipped: {why}");
        return None;
    }
    assert!(status.success(), "{test}: voodoo {args:?}: {stderr}");
    Some(std::fs::read(&capture).unwrap_or_else(|e| panic!("{test}: {}: {e}", capture.display())))
}

/// The RGB bytes of a binary PPM, and its size.
fn ppm(bytes: &[u8]) -> (u32, u32, &[u8]) {
    let text = std::str::from_utf8(&bytes[..bytes.len().min(32)]).unwrap_or("");
    let mut fields = text.split_ascii_whitespace();
    assert_eq!(fields.next(), Some("P6"));
    let w: u32 = fields.next().unwrap().parse().unwrap();
    let h: u32 = fields.next().unwrap().parse().unwrap();
    assert_eq!(fields.next(), Some("255"));
    let header = format!("P6\n{w} {h}\n255\n").len();
    (w, h, &bytes[header..])
}

fn assert_window_is_png(test: &str, capture: &[u8], png: &Path) {
    let (w, h, rgb) = ppm(capture);
    let image = image::open(png).unwrap().to_rgb8();
    assert_eq!((w, h), (image.width(), image.height()), "{test}: size");
    let differ = rgb
        .chunks_exact(3)
        .zip(image.as_raw().chunks_exact(3))
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differ, 0,
        "{test}: pixels differ between the window and the PNG"
    );
    assert_eq!(rgb.len(), image.as_raw().len());
}

#[test]
fn the_demo_window_shows_the_png() {
    let test = "the_demo_window_shows_the_png";
    let Some(server) = Server::start(test) else {
        return;
    };
    let dir = scratch("demo");
    if let Some(capture) = run_captured(test, &server, &dir, &["demo", "--png", "demo.png"]) {
        assert_window_is_png(test, &capture, &dir.join("demo.png"));
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn the_player_window_shows_the_first_frame() {
    let test = "the_player_window_shows_the_first_frame";
    let Some(server) = Server::start(test) else {
        return;
    };
    let dir = scratch("play");
    let trace = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces/conformance/traces/gouraud_dither4.trace.gz");
    let trace = trace.to_str().unwrap();
    // The trace's one frame, as `replay` writes it.
    let replayed = Command::new(env!("CARGO_BIN_EXE_voodoo"))
        .args(["replay", trace, "--png", "frame.png", "--out", "dumps"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(replayed.status.success(), "{replayed:?}");
    if let Some(capture) = run_captured(test, &server, &dir, &["play", trace]) {
        assert_window_is_png(test, &capture, &dir.join("frame.png"));
    }
    std::fs::remove_dir_all(dir).unwrap();
}
