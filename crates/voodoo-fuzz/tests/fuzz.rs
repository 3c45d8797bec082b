//! The fuzz harness as tests: a bounded seeded run for CI, and a long run on request.
//!
//! * `cargo test --release -p voodoo-fuzz`: the bounded run (a few seconds).
//! * `VOODOO_FUZZ_SECS=3600 cargo test --release -p voodoo-fuzz -- --ignored`: an hour
//!   (with `--nocapture` to see the report). See the crate docs for the other variables.

use voodoo_fuzz::{describe, run, Config};

/// Cases of the bounded run: a few seconds on two cores.
const CI_CASES: u64 = 6000;

fn run_and_check(config: &Config) {
    let report = run(config);
    let text = describe(&report, config);
    eprint!("{text}");
    assert!(report.failures.is_empty(), "{text}");
    assert!(report.cases.iter().all(|(_, n)| *n > 0), "{text}");
}

#[test]
fn bounded_seeded_run() {
    run_and_check(&Config::from_env(CI_CASES));
}

#[test]
#[ignore = "long: set VOODOO_FUZZ_SECS (default 600) and run with --ignored"]
fn long_run() {
    let mut config = Config::from_env(0);
    if std::env::var_os("VOODOO_FUZZ_SECS").is_none()
        && std::env::var_os("VOODOO_FUZZ_CASES").is_none()
    {
        config.budget = voodoo_fuzz::Budget::Time(std::time::Duration::from_secs(600));
    }
    run_and_check(&config);
}

/// Every target accepts empty and tiny inputs, and its seeds.
#[test]
fn targets_take_their_seeds() {
    let repo = voodoo_fuzz::corpus::Repository::load();
    assert!(repo.traces().len() >= 3, "repository traces not found");
    for target in voodoo_fuzz::targets::TARGETS {
        for input in [&b""[..], b"\n", b"\x1f\x8b", b"SST1TRCB"] {
            voodoo_fuzz::run_one(target, input).unwrap_or_else(|e| panic!("{}: {e}", target.name));
        }
        let seeds = (target.seeds)(&repo);
        assert!(!seeds.is_empty(), "{}", target.name);
        for seed in seeds {
            voodoo_fuzz::run_one(target, &seed).unwrap_or_else(|e| panic!("{}: {e}", target.name));
        }
    }
}
