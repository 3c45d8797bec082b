//! Robustness: thousands of random and mutated inputs to both parsers, from a seeded PRNG
//! (so a failure reproduces). No input may panic, and whatever parses must survive both
//! round trips unchanged.

use std::io::Write;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;

use sst1_trace::{decode_binary, encode_binary, parse_text, read_trace, write_text, Trace};

/// xorshift64* (Vigna 2016): small, deterministic, good enough to pick mutations.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len())]
    }
}

/// Checks that a trace that parsed survives text and binary round trips.
fn assert_round_trips(trace: &Trace) {
    let text = write_text(trace);
    assert_eq!(&parse_text("re", text.as_bytes()).unwrap(), trace);
    assert_eq!(&decode_binary(&encode_binary(trace)).unwrap(), trace);
}

/// Runs both parsers on `input`; a panic or a broken round trip fails with the input shown.
fn check(case: usize, input: &[u8]) {
    let result = catch_unwind(AssertUnwindSafe(|| {
        if let Ok(trace) = parse_text("fuzz", input) {
            assert_round_trips(&trace);
        }
        if let Ok(trace) = read_trace("fuzz", input) {
            assert_round_trips(&trace);
        }
        if let Ok(trace) = decode_binary(input) {
            assert_round_trips(&trace);
        }
    }));
    if result.is_err() {
        panic!("case {case}: input {input:02x?}");
    }
}

fn mutate(rng: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut bytes = seed.to_vec();
    for _ in 0..1 + rng.below(8) {
        let at = rng.below(bytes.len() + 1);
        match rng.below(5) {
            0 if at < bytes.len() => bytes[at] ^= 1 << rng.below(8),
            1 if at < bytes.len() => bytes[at] = rng.next() as u8,
            2 => bytes.insert(at, rng.next() as u8),
            3 if at < bytes.len() => {
                bytes.remove(at);
            }
            _ => bytes.truncate(at),
        }
    }
    bytes
}

fn random_line(rng: &mut Rng) -> String {
    const WORDS: &[&str] = &[
        "config",
        "pci",
        "w",
        "r",
        "dump",
        "fbi_mb",
        "tmus",
        "tmu_mb",
        "front",
        "back",
        "depth",
        "aux",
        "0x40",
        "0x000210",
        "0x00000003",
        "4",
        "2",
        "1",
        "0",
        "0x",
        "0xffffffff",
        "4294967296",
        "0x1000000",
        "0xfffffc",
        "a.raw",
        "..",
        "x/y",
        "#",
        "# comment",
        "\t",
        "\r",
        "é",
        "W",
        "-1",
        "+3",
        "0x0g",
        "00012",
    ];
    const NUMBERS: &[&str] = &["0x40", "0x000210", "0x00000003", "4", "0", "0xfffffc", "64"];
    // Mostly well-formed commands, with now and then a word from anywhere.
    let mut words: Vec<&str> = match rng.below(6) {
        0 => vec![
            "config",
            rng.pick(&["fbi_mb", "tmus", "tmu_mb"]),
            rng.pick(&["1", "2", "4"]),
        ],
        1 => vec!["pci", rng.pick(NUMBERS), rng.pick(NUMBERS)],
        2 => vec!["w", rng.pick(NUMBERS), rng.pick(NUMBERS)],
        3 => vec!["r", rng.pick(NUMBERS), rng.pick(&["", "0x1", "#"])],
        4 => vec![
            "dump",
            rng.pick(&["front", "back", "depth", "aux"]),
            rng.pick(&["a.raw", "b"]),
        ],
        _ => (0..rng.below(5)).map(|_| rng.pick(WORDS)).collect(),
    };
    if rng.below(4) == 0 {
        let at = rng.below(words.len() + 1);
        words.insert(at, rng.pick(WORDS));
    }
    let mut line = String::new();
    for word in words {
        line.push_str(word);
        line.push(if rng.below(8) == 0 { '\t' } else { ' ' });
    }
    line
}

#[test]
fn random_and_mutated_inputs_never_panic() {
    let mut rng = Rng(0x5eed_f0e5_5571);
    let trace_path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces/conformance/traces/fastfill_depth.trace.gz");
    let gz = std::fs::read(trace_path).unwrap();
    let real = parse_text("fastfill_depth", &gz).unwrap();
    let text = write_text(&real).into_bytes();
    let binary = encode_binary(&real);
    let small_gz = {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(&text[..text.len().min(600)]).unwrap();
        enc.finish().unwrap()
    };

    let mut case = 0;
    let mut parsed = 0;
    for _ in 0..1000 {
        // Random bytes.
        let len = rng.below(64);
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        check(case, &bytes);
        case += 1;

        // Lines built from the format's own words.
        let lines: Vec<String> = (0..1 + rng.below(6))
            .map(|_| random_line(&mut rng))
            .collect();
        let input = lines.join("\n");
        parsed += usize::from(parse_text("fuzz", input.as_bytes()).is_ok());
        check(case, input.as_bytes());
        case += 1;

        // A real trace, mutated (text, gzip and binary forms).
        let start = rng.below(text.len() - 200);
        check(case, &mutate(&mut rng, &text[start..start + 200]));
        check(case + 1, &mutate(&mut rng, &small_gz));
        check(case + 2, &mutate(&mut rng, &binary));
        case += 3;
    }
    assert_eq!(case, 5000);
    // The grammar-based lines must reach the success path too, or the round-trip check is idle.
    assert!(parsed > 100, "only {parsed} generated inputs parsed");
}
