//! The generated traces checked in under `traces/generated/` are what the generators of
//! `sst1_trace::scenes` write for the seeds and sizes `traces/generated/README.md`
//! names. After an intended change to a generator, rewrite them with
//! `VOODOO_BLESS=1 cargo test -p sst1-trace --test scenes`.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use sst1_trace::scenes::{random_states, small_triangles, stability, RandomStates};

fn generated_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces/generated")
}

/// Each checked-in file (under `traces/`) and the text its generator writes now.
fn expected() -> Vec<(String, String)> {
    let mut files = vec![
        (
            "generated/small_tris.trace.gz".to_owned(),
            small_triangles(1, 2000, false),
        ),
        (
            "generated/random_states.trace.gz".to_owned(),
            random_states(RandomStates {
                seed: 1,
                tmus: 2,
                states: 100,
                ..RandomStates::default()
            }),
        ),
    ];
    // `voodoo gen stability --family NAME --out traces/stability/NAME.trace.gz`.
    for f in &stability::FAMILIES {
        files.push((
            format!("stability/{}.trace.gz", f.name),
            stability::scene(f),
        ));
    }
    files
}

#[test]
fn generated_traces_match_their_generators() {
    let bless = std::env::var_os("VOODOO_BLESS").is_some();
    for (file, text) in expected() {
        let path = generated_dir().join("..").join(file);
        if bless {
            let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
            gz.write_all(text.as_bytes()).unwrap();
            std::fs::write(&path, gz.finish().unwrap()).unwrap();
            continue;
        }
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let mut found = String::new();
        flate2::read::GzDecoder::new(&bytes[..])
            .read_to_string(&mut found)
            .unwrap();
        assert!(
            found == text,
            "{} is not what its generator writes now; after an intended change run \
             VOODOO_BLESS=1 cargo test -p sst1-trace --test scenes",
            path.display()
        );
    }
}
