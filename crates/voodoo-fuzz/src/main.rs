//! `voodoo-fuzz`: runs the fuzz harness for as long as asked, or one saved input.
//!
//! ```text
//! voodoo-fuzz [--secs N | --cases N] [--seed S] [--targets a,b]   a run (default: 1 hour)
//! voodoo-fuzz --repro TARGET FILE                                 one saved input
//! voodoo-fuzz --list                                              the targets
//! ```
//! Environment variables as for the harness (`VOODOO_FUZZ_*`, see the crate docs) set
//! the defaults; arguments override them.

use std::process::ExitCode;
use std::time::Duration;

use voodoo_fuzz::{describe, run, target, Budget, Config};

fn usage() -> ExitCode {
    eprintln!(
        "usage: voodoo-fuzz [--secs N | --cases N] [--seed S] [--targets a,b] | --repro TARGET FILE | --list"
    );
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut config = Config::from_env(0);
    if std::env::var_os("VOODOO_FUZZ_SECS").is_none()
        && std::env::var_os("VOODOO_FUZZ_CASES").is_none()
    {
        config.budget = Budget::Time(Duration::from_secs(3600));
    }
    let mut i = 0;
    while i < args.len() {
        let value = args.get(i + 1).map(String::as_str);
        let number = value.and_then(|v| match v.strip_prefix("0x") {
            Some(hex) => u64::from_str_radix(hex, 16).ok(),
            None => v.parse().ok(),
        });
        match (args[i].as_str(), number) {
            ("--list", _) => {
                for t in voodoo_fuzz::targets::TARGETS {
                    println!("{:<10} {}", t.name, t.about);
                }
                return ExitCode::SUCCESS;
            }
            ("--repro", _) => {
                let (Some(name), Some(file)) = (args.get(i + 1), args.get(i + 2)) else {
                    return usage();
                };
                let Some(target) = target(name) else {
                    eprintln!("voodoo-fuzz: no target named {name:?}");
                    return ExitCode::from(2);
                };
                let input = match std::fs::read(file) {
                    Ok(input) => input,
                    Err(e) => {
                        eprintln!("voodoo-fuzz: {file}: {e}");
                        return ExitCode::from(2);
                    }
                };
                // Without catch_unwind: the panic and its backtrace show.
                (target.run)(&input);
                println!("{name}: {file} passes");
                return ExitCode::SUCCESS;
            }
            ("--secs", Some(n)) => config.budget = Budget::Time(Duration::from_secs(n)),
            ("--cases", Some(n)) => config.budget = Budget::Cases(n),
            ("--seed", Some(n)) => config.seed = n,
            ("--targets", _) if value.is_some() => {
                config.targets = value.map(|v| v.split(',').map(str::to_owned).collect());
            }
            _ => return usage(),
        }
        i += 2;
    }
    let report = run(&config);
    print!("{}", describe(&report, &config));
    if report.failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
