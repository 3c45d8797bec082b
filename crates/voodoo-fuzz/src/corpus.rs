//! Seed inputs: pieces of the repository's traces in each form, and a few written here.

use std::io::Write;
use std::path::{Path, PathBuf};

use sst1_trace::{encode_binary, write_text, Trace, TraceOp};

/// How many of the repository's traces seed a run (the smallest files: quick to load).
const TRACES: usize = 6;
/// How many ops of a trace one seed piece holds.
pub const SEED_OPS: usize = 300;

/// The repository's traces that seed a run.
pub struct Repository {
    root: PathBuf,
    traces: Vec<(String, Trace)>,
}

impl Repository {
    /// Loads the smallest trace files of `traces/*/traces/` and `traces/examples/`.
    pub fn load() -> Self {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let mut files: Vec<(u64, PathBuf)> = Vec::new();
        for dir in [
            "traces/conformance/traces",
            "traces/glide-sdk/traces",
            "traces/examples",
        ] {
            let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
                continue;
            };
            for entry in entries.flatten() {
                let path = entry.path();
                let is_trace = path.to_string_lossy().ends_with(".trace.gz");
                if let (true, Ok(meta)) = (is_trace, entry.metadata()) {
                    files.push((meta.len(), path));
                }
            }
        }
        files.sort();
        let traces = files
            .into_iter()
            .take(TRACES)
            .filter_map(|(_, path)| {
                let name = path.file_name()?.to_string_lossy().into_owned();
                Some((name, sst1_trace::load_trace(&path).ok()?))
            })
            .collect();
        Self { root, traces }
    }

    /// The repository's root folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The loaded traces, by file name.
    pub fn traces(&self) -> &[(String, Trace)] {
        &self.traces
    }

    /// Pieces of each trace, [`SEED_OPS`] ops each: its start (with its `config` ops and
    /// init writes) and one from its middle.
    pub fn pieces(&self) -> Vec<Trace> {
        let mut pieces = Vec::new();
        for (_, trace) in &self.traces {
            let ops = &trace.ops;
            pieces.push(Trace {
                ops: ops[..ops.len().min(SEED_OPS)].to_vec(),
            });
            let mid = ops.len() / 2;
            let middle: Vec<TraceOp> = ops[mid..ops.len().min(mid + SEED_OPS)]
                .iter()
                .filter(|op| !matches!(op, TraceOp::Config { .. }))
                .cloned()
                .collect();
            pieces.push(Trace { ops: middle });
        }
        pieces
    }
}

/// Text seeds written here: the grammar's corners.
const TEXT_SEEDS: &[&str] = &[
    "config fbi_mb 2\nconfig tmus 3\nconfig tmu_mb 1\npci 0x40 0x3\nw 0x000124 0\ndump front a.raw\n",
    "  # header\nconfig tmus 2 # two\r\npci 64 0x00000003\nw 0x000210 4294967295\n",
    "r 0xffc\nr 0 0X10\ndump aux z.raw\ndump depth d\ndump back b\n",
    "pci 0x40 3\nw 0x000118 0x00000010\nw 0x00011c 0x00000010\nw 0x000148 0x00858585\n\
     w 0x000110 0x00000b01\nw 0x000124 0\nw 0x000128 1\ndump front fill_front.raw\n",
];

/// The text form of the repository pieces, and the seeds written here.
pub fn text_seeds(repo: &Repository) -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = TEXT_SEEDS.iter().map(|s| s.as_bytes().to_vec()).collect();
    seeds.extend(repo.pieces().iter().map(|t| write_text(t).into_bytes()));
    seeds
}

/// The binary form of the repository pieces and of the text seeds.
pub fn binary_seeds(repo: &Repository) -> Vec<Vec<u8>> {
    let mut seeds: Vec<Vec<u8>> = repo.pieces().iter().map(encode_binary).collect();
    for text in TEXT_SEEDS {
        if let Ok(trace) = sst1_trace::parse_text("seed", text.as_bytes()) {
            seeds.push(encode_binary(&trace));
        }
    }
    seeds
}

/// Gzip-compresses `bytes`.
pub fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
    // Writing to a Vec cannot fail.
    let _ = enc.write_all(bytes);
    enc.finish().unwrap_or_default()
}

/// Every form: text, binary, and each gzip-compressed.
pub fn any_form_seeds(repo: &Repository) -> Vec<Vec<u8>> {
    let mut seeds = text_seeds(repo);
    seeds.extend(binary_seeds(repo));
    let compressed: Vec<Vec<u8>> = seeds.iter().take(8).map(|s| gzip(s)).collect();
    seeds.extend(compressed);
    seeds
}
