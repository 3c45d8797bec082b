//! The text and binary formats: round trips on every repository trace, exact error
//! messages, the recorder, op counting and replay output files.

use std::path::{Path, PathBuf};

use sst1_board::{Board, BoardConfig};
use sst1_regs::RegisterBus;
use sst1_trace::{
    decode_binary, encode_binary, execute, parse_text, read_trace, replay, rgb565_to_rgb8,
    write_text, BinaryError, ConfigKey, DumpBuffer, OpCounts, Recorder, Trace, TraceOp,
};

fn traces_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../traces")
}

fn all_trace_files() -> Vec<PathBuf> {
    let mut files = Vec::new();
    for suite in ["conformance", "glide-sdk"] {
        let dir = traces_dir().join(suite).join("traces");
        for entry in std::fs::read_dir(&dir).unwrap() {
            files.push(entry.unwrap().path());
        }
    }
    files.sort();
    files
}

#[test]
fn every_repository_trace_round_trips_text_and_binary() {
    let files = all_trace_files();
    assert_eq!(files.len(), 41 + 18);
    for path in files {
        let name = path.display().to_string();
        let bytes = std::fs::read(&path).unwrap();
        let trace = parse_text(&name, &bytes).unwrap_or_else(|e| panic!("{e}"));
        assert!(trace.ops.len() > 100, "{name}");

        // text -> text
        let text = write_text(&trace);
        assert_eq!(
            parse_text("rewritten", text.as_bytes()).unwrap(),
            trace,
            "{name}"
        );

        // text -> binary -> text, and binary -> binary is byte-identical
        let encoded = encode_binary(&trace);
        let decoded = decode_binary(&encoded).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(decoded, trace, "{name}");
        assert_eq!(encode_binary(&decoded), encoded, "{name}");
        assert_eq!(write_text(&decoded), text, "{name}");

        // read_trace recognises the binary form too
        assert_eq!(read_trace("binary", &encoded).unwrap(), trace, "{name}");
    }
}

#[test]
fn gouraud_dither4_counts() {
    let path = traces_dir().join("conformance/traces/gouraud_dither4.trace.gz");
    let trace = parse_text("gouraud_dither4", &std::fs::read(path).unwrap()).unwrap();
    assert_eq!(
        trace.board_config(),
        BoardConfig {
            fbi_mb: 4,
            tmus: 1,
            tmu_mb: 4
        }
    );
    assert_eq!(
        trace.ops[3],
        TraceOp::Pci {
            offset: 0x40,
            value: 3
        }
    );
    assert_eq!(
        trace.ops[4],
        TraceOp::Write {
            addr: 0x210,
            value: 7
        }
    );
    let dumps: Vec<_> = trace
        .ops
        .iter()
        .filter_map(|op| match op {
            TraceOp::Dump { buffer, file } => Some((*buffer, file.as_str())),
            _ => None,
        })
        .collect();
    assert_eq!(
        dumps,
        [
            (DumpBuffer::Front, "gouraud_dither4_front.raw"),
            (DumpBuffer::Depth, "gouraud_dither4_depth.raw")
        ]
    );
}

/// (input, exact error message)
const BAD_LINES: &[(&[u8], &str)] = &[
    (b"w 0x10 1\nfoo 1 2\n", "t.trace:2: unknown command `foo`; expected config, pci, w, r, wait or dump"),
    (b"# c\n\nw 0x10\n", "t.trace:3: expected a 32-bit value (0x hex or decimal), found end of line"),
    (b"w 0x10 0x1ffffffff\n", "t.trace:1: expected a 32-bit value (0x hex or decimal), found `0x1ffffffff`"),
    (b"w 0x10 12a\n", "t.trace:1: expected a 32-bit value (0x hex or decimal), found `12a`"),
    (b"w 0x10 +5\n", "t.trace:1: expected a 32-bit value (0x hex or decimal), found `+5`"),
    (b"w 0x10 0x\n", "t.trace:1: expected a 32-bit value (0x hex or decimal), found `0x`"),
    (b"w 0x12 0\n", "t.trace:1: expected a 4-aligned aperture offset below 0x1000000, found `0x12`"),
    (b"\n\n\n\nw 0x1000000 0\n", "t.trace:5: expected a 4-aligned aperture offset below 0x1000000, found `0x1000000`"),
    (b"w\n", "t.trace:1: expected a 4-aligned aperture offset below 0x1000000, found end of line"),
    (b"w 0x10 1 2\n", "t.trace:1: expected end of line, found `2`"),
    (b"pci 0x100 3\n", "t.trace:1: expected a 4-aligned PCI configuration offset below 0x100, found `0x100`"),
    (b"config fbi_mb 3\n", "t.trace:1: expected fbi_mb 2 or 4, found `3`"),
    (b"config tmus 0\n", "t.trace:1: expected tmus 1, 2 or 3, found `0`"),
    (b"config tmu_mb 8\n", "t.trace:1: expected tmu_mb 1, 2 or 4, found `8`"),
    (b"config colour 1\n", "t.trace:1: expected a config key (fbi_mb, tmus or tmu_mb), found `colour`"),
    (b"config tmus 1\nw 0 0\nconfig tmus 2\n", "t.trace:3: `config` after the first write; config lines must come first"),
    (b"dump left a.raw\n", "t.trace:1: expected a buffer (front, back, depth or aux), found `left`"),
    (b"dump front\n", "t.trace:1: expected a bare file name (no path separators, whitespace or `#`, at most 255 bytes), found end of line"),
    (b"dump front ../x.raw\n", "t.trace:1: expected a bare file name (no path separators, whitespace or `#`, at most 255 bytes), found `../x.raw`"),
    (b"dump front ..\n", "t.trace:1: expected a bare file name (no path separators, whitespace or `#`, at most 255 bytes), found `..`"),
    (b"r 0x0 0x1 0x2\n", "t.trace:1: expected end of line, found `0x2`"),
    (b"w 0 0\r\nw 0 0\nw\xff 0 0\n", "t.trace:3: not UTF-8 text"),
    (b"\x1f\x8b\x08\x00garbage", "t.trace: cannot decompress: incomplete deflate stream"),
];

#[test]
fn malformed_lines_name_file_line_and_expectation() {
    for (input, message) in BAD_LINES {
        let err = parse_text("t.trace", input).expect_err(message);
        assert_eq!(
            err.to_string(),
            *message,
            "input {:?}",
            String::from_utf8_lossy(input)
        );
    }
}

#[test]
fn accepted_syntax() {
    let text = "  # header\nconfig tmus 2 # two\r\nconfig tmus 3\npci 64 0x00000003\n\
                w 0x000210 4294967295\nW_IS_NOT\n";
    // The last line is an unknown command; everything before it parses.
    assert!(parse_text("t", text.as_bytes()).is_err());
    let text = &text[..text.len() - "W_IS_NOT\n".len()];
    let trace = parse_text("t", text.as_bytes()).unwrap();
    assert_eq!(
        trace.ops,
        [
            TraceOp::Config {
                key: ConfigKey::Tmus,
                value: 2
            },
            TraceOp::Config {
                key: ConfigKey::Tmus,
                value: 3
            },
            TraceOp::Pci {
                offset: 0x40,
                value: 3
            },
            TraceOp::Write {
                addr: 0x210,
                value: 0xffff_ffff
            },
        ]
    );
    assert_eq!(
        trace.board_config(),
        BoardConfig {
            fbi_mb: 4,
            tmus: 3,
            tmu_mb: 4
        }
    );
    assert_eq!(
        write_text(&trace),
        "config tmus 2\nconfig tmus 3\npci 0x40 0x00000003\nw 0x000210 0xffffffff\n"
    );
    let reads = parse_text("t", b"r 0xffc\nr 0 0X10\ndump aux z.raw").unwrap();
    assert_eq!(
        reads.ops,
        [
            TraceOp::Read {
                addr: 0xffc,
                value: None
            },
            TraceOp::Read {
                addr: 0,
                value: Some(16)
            },
            TraceOp::Dump {
                buffer: DumpBuffer::Aux,
                file: "z.raw".into()
            },
        ]
    );
    assert_eq!(
        write_text(&reads),
        "r 0x000ffc\nr 0x000000 0x00000010\ndump aux z.raw\n"
    );
}

fn small_trace() -> Trace {
    parse_text(
        "t",
        b"config fbi_mb 2\npci 0x40 3\nw 0x128 1\nr 0x0 7\ndump depth d.raw\n",
    )
    .unwrap()
}

#[test]
fn binary_layout_and_errors() {
    let bytes = encode_binary(&small_trace());
    #[rustfmt::skip]
    let expected: &[u8] = &[
        b'S', b'S', b'T', b'1', b'T', b'R', b'C', b'B',
        1, 0, 1, 0, 36, 0, 0, 0, // version, min_reader_version, header_len
        2, 1, 4, 0, // fbi_mb, tmus, tmu_mb, reserved
        5, 0, 0, 0, 0, 0, 0, 0, // op_count
        1, 0, 0, 0, 0, 0, 0, 0, // frame_count
        0x01, 0, 2, 0, 0, 0, // config fbi_mb 2
        0x02, 0x40, 0, 0, 0, 3, 0, 0, 0, // pci
        0x03, 0x28, 1, 0, 0, 1, 0, 0, 0, // w swapbufferCMD
        0x07, 0, 0, 0, 0, // frame 0
        0x05, 0, 0, 0, 0, 7, 0, 0, 0, // r with value
        0x06, 2, 5, b'd', b'.', b'r', b'a', b'w', // dump depth
    ];
    assert_eq!(bytes, expected);

    let mut too_new = bytes.clone();
    too_new[10] = 3;
    assert_eq!(
        decode_binary(&too_new),
        Err(BinaryError::TooNew {
            version: 1,
            min_reader_version: 3
        })
    );
    // A newer writer that old readers can still read: longer header, skipped.
    let mut newer = bytes[..36].to_vec();
    newer[8] = 7;
    newer[12] = 40;
    newer.extend_from_slice(&[9, 9, 9, 9]);
    newer.extend_from_slice(&bytes[36..]);
    assert_eq!(decode_binary(&newer).unwrap(), small_trace());

    assert_eq!(decode_binary(b"SST1TRCA"), Err(BinaryError::BadMagic));
    assert_eq!(
        decode_binary(&bytes[..bytes.len() - 1])
            .unwrap_err()
            .to_string(),
        "byte 74: file ends inside a record"
    );
    let mut no_frame = bytes.clone();
    no_frame.drain(60..65);
    assert_eq!(
        decode_binary(&no_frame).unwrap_err().to_string(),
        "byte 60: expected a frame record after a swap"
    );
    let mut bad_count = bytes.clone();
    bad_count[20] = 6;
    assert_eq!(
        decode_binary(&bad_count).unwrap_err().to_string(),
        "header says 6 ops, 1 frames, board [2, 1, 4], records hold 5 ops, 1 frames, board [2, 1, 4]"
    );
    let mut bad_tag = bytes.clone();
    bad_tag[36] = 0x42;
    assert_eq!(
        decode_binary(&bad_tag).unwrap_err().to_string(),
        "byte 36: unknown record tag 0x42"
    );
    let mut bad_addr = bytes.clone();
    bad_addr[52] = 0x29;
    assert_eq!(
        decode_binary(&bad_addr).unwrap_err().to_string(),
        "byte 51: expected a 4-aligned aperture offset below 0x1000000"
    );
}

/// A bus that remembers the last write and answers reads with `addr + 1`.
#[derive(Default)]
struct FakeBus {
    log: Vec<(char, u32, u32)>,
}

impl RegisterBus for FakeBus {
    fn write32(&mut self, addr: u32, value: u32) {
        self.log.push(('w', addr, value));
    }
    fn read32(&mut self, addr: u32) -> u32 {
        addr + 1
    }
    fn pci_write(&mut self, offset: u32, value: u32) {
        self.log.push(('p', offset, value));
    }
}

#[test]
fn recorder_forwards_and_logs() {
    let mut rec = Recorder::new(
        FakeBus::default(),
        BoardConfig {
            fbi_mb: 2,
            tmus: 2,
            tmu_mb: 1,
        },
    );
    rec.pci_write(0x40, 3);
    rec.write32(0x124, 0);
    assert_eq!(rec.read32(0x14c), 0x14d);
    rec.dump(DumpBuffer::Front, "f.raw");
    let (bus, trace) = rec.finish();
    assert_eq!(bus.log, [('p', 0x40, 3), ('w', 0x124, 0)]);
    let expected = "config fbi_mb 2\nconfig tmus 2\nconfig tmu_mb 1\npci 0x40 0x00000003\n\
                    w 0x000124 0x00000000\nr 0x00014c 0x0000014d\ndump front f.raw\n";
    assert_eq!(write_text(&trace), expected);
    assert_eq!(decode_binary(&encode_binary(&trace)).unwrap(), trace);
}

#[test]
fn op_counts_mind_chip_and_wrap_bits() {
    let text = "w 0x080 0\n\
                w 0x100 0\n\
                w 0x500 0\n\
                w 0x900 0\n\
                w 0x300080 0\n\
                w 0x000d24 0\n\
                w 0x000528 0\n\
                w 0x001128 0\n\
                w 0x400000 0\n\
                w 0x800000 0\n\
                pci 0x40 1\n\
                r 0 0\n\
                dump front a.raw\n";
    let counts = OpCounts::of(&parse_text("t", text.as_bytes()).unwrap());
    assert_eq!(counts.writes, 10);
    assert_eq!((counts.reads, counts.pci, counts.dumps), (1, 1, 1));
    assert_eq!(
        (
            counts.register_writes,
            counts.lfb_writes,
            counts.texture_writes
        ),
        (8, 1, 1)
    );
    // 0x080, 0x100, 0x500 (FBI chip bit), 0x300080 (wrap bits): triangles; 0x900 is TMU0 only.
    assert_eq!(counts.triangles, 4);
    // 0x000d24: chip bits FBI + TMU0.
    assert_eq!(counts.fastfills, 1);
    // 0x000528 (offset 0x128 with bit 10) counts, 0x001128 (TMU1 only) does not.
    assert_eq!(counts.swaps, 1);
    let registers: Vec<_> = counts.registers.into_iter().collect();
    assert_eq!(registers, [(0x080, 2), (0x100, 3), (0x124, 1), (0x128, 2)]);
}

#[test]
#[allow(clippy::unusual_byte_groupings)] // grouped as the R/G/B fields: 5, 6, 5 bits
fn rgb565_expansion_replicates_high_bits() {
    assert_eq!(rgb565_to_rgb8(0x0000), [0, 0, 0]);
    assert_eq!(rgb565_to_rgb8(0xffff), [255, 255, 255]);
    assert_eq!(rgb565_to_rgb8(0xf800), [255, 0, 0]);
    assert_eq!(rgb565_to_rgb8(0x07e0), [0, 255, 0]);
    // r = 0b10000 -> 0b10000100, g = 0b100000 -> 0b10000010, b = 0b00001 -> 0b00001000
    assert_eq!(rgb565_to_rgb8(0b10000_100000_00001), [0x84, 0x82, 0x08]);
}

#[test]
fn replay_writes_dumps_into_out_dir() {
    let dir = std::env::temp_dir().join(format!("sst1-trace-replay-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let trace = small_trace();
    let mut board = Board::new(trace.board_config());
    let written = replay(trace.ops.iter().cloned().map(Ok), &mut board, &dir).unwrap();
    assert_eq!(written, 1);
    let dumps = execute(&trace.ops, &mut Board::new(trace.board_config()), |_| {});
    let (w, h) = board.display_size();
    assert_eq!((dumps[0].width, dumps[0].height), (w, h));
    assert_eq!(dumps[0].data.len(), (w * h) as usize);
    let written = std::fs::read(dir.join("d.raw")).unwrap();
    assert_eq!(written, dumps[0].to_le_bytes());
    assert_eq!(written.len(), (w * h * 2) as usize);
    std::fs::remove_dir_all(&dir).unwrap();
}
