//! Xvfb for the window tests (voodoo-cli's and glide3-c's `window` tests include this
//! file): a virtual X server on a display it picks itself, or `None`, said on stderr,
//! where there is no Xvfb on the PATH.

use std::io::{BufRead, BufReader};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};

/// `Xvfb` on the PATH, if there is one.
fn xvfb() -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|d| d.join("Xvfb"))
            .find(|p| p.is_file())
    })
}

/// A running Xvfb on a display it chose itself (`-displayfd`), killed when dropped.
pub struct Server {
    child: Child,
    pub display: String,
}

impl Server {
    /// Starts Xvfb; `None` (said on stderr) where there is none or it does not start.
    pub fn start(test: &str) -> Option<Self> {
        let Some(bin) = xvfb() else {
            eprintln!("{test}: skipped: no Xvfb on the PATH (Debian: apt-get install xvfb)");
            return None;
        };
        let mut child = Command::new(bin)
            .args([
                "-displayfd",
                "1",
                "-screen",
                "0",
                "800x600x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .ok()?;
        // Xvfb writes the display number once it accepts connections.
        let mut line = String::new();
        let read = child
            .stdout
            .take()
            .map(|out| BufReader::new(out).read_line(&mut line));
        let number = line.trim();
        if !matches!(read, Some(Ok(n)) if n > 0) || number.is_empty() {
            let _ = child.kill();
            let _ = child.wait();
            eprintln!("{test}: skipped: Xvfb did not start");
            return None;
        }
        Some(Self {
            display: format!(":{number}"),
            child,
        })
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
