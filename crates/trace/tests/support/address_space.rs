//! The address-space limit of the tests that run a child process under bounded memory,
//! shared by `sst1-trace`'s, `voodoo-cli`'s and `glide3-c`'s tests (each includes this
//! file with `#[path]`).

use std::os::unix::process::CommandExt;
use std::process::Command;

/// Limits the address space of the process `command` starts to `bytes` (`RLIMIT_AS`).
pub fn limit_address_space(command: &mut Command, bytes: u64) {
    // SAFETY: setrlimit is async-signal-safe and touches no memory of the parent.
    unsafe {
        command.pre_exec(move || {
            let rlim = libc::rlimit {
                rlim_cur: bytes as libc::rlim_t,
                rlim_max: bytes as libc::rlim_t,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &rlim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
}
