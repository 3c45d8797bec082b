//! The live window of libglide3 from the default build (`VOODOO_WINDOW=1`) under Xvfb:
//! `tests/window_swaps.c` swaps one frame until the window has written what it
//! presented (`VOODOO_WINDOW_CAPTURE`); that must be the PNG `VOODOO_PNG` wrote of the
//! same frame, pixel for pixel. Where there is no Xvfb on the PATH (or no
//! libxkbcommon-x11 at run time), the test says so on stderr and passes unchecked.

#[path = "../../sst1-window/tests/support/xvfb.rs"]
mod xvfb;

use std::path::{Path, PathBuf};
use std::process::Command;

/// Where cargo built this package's cdylib for the tests (see c_examples.rs).
fn lib_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    exe.parent().expect("target deps dir").to_path_buf()
}

#[test]
fn the_live_window_shows_the_swapped_frame() {
    let test = "the_live_window_shows_the_swapped_frame";
    let Some(server) = xvfb::Server::start(test) else {
        return;
    };
    let dir = std::env::temp_dir().join(format!("glide3-window-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let exe = dir.join("window_swaps");
    let built = Command::new("cc")
        .args(["-std=gnu17", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(here.join("include"))
        .arg(here.join("tests/window_swaps.c"))
        .arg("-L")
        .arg(lib_dir())
        .args(["-lglide3", "-lm", "-lpthread", "-o"])
        .arg(&exe)
        .status()
        .expect("run cc");
    assert!(built.success(), "compiling window_swaps.c failed");
    let capture = dir.join("capture.ppm");
    let png = dir.join("frame.png");
    let run = Command::new(&exe)
        .env("LD_LIBRARY_PATH", lib_dir())
        .env("DISPLAY", &server.display)
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .env("VOODOO_WINDOW", "1")
        .env("VOODOO_WINDOW_CAPTURE", &capture)
        .env("VOODOO_PNG", &png)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    if stderr.contains("running headless") {
        eprintln!("{test}: skipped: {}", stderr.trim());
        let _ = std::fs::remove_dir_all(&dir);
        return;
    }
    assert!(run.status.success(), "{run:?}");
    let bytes = std::fs::read(&capture).unwrap();
    let header = b"P6\n640 480\n255\n";
    assert!(bytes.starts_with(header), "capture header");
    let image = image::open(&png).unwrap().to_rgb8();
    assert_eq!((image.width(), image.height()), (640, 480));
    assert!(
        &bytes[header.len()..] == image.as_raw().as_slice(),
        "the window's pixels differ from the PNG's"
    );
    std::fs::remove_dir_all(dir).unwrap();
}
