//! The pixel watch (`Board::watch_pixel`, `pixelfx::watch`) against the pipeline's own
//! result: a watched replay draws exactly what an unwatched one does (the watch only
//! observes), the last event that wrote the watched pixel wrote the value the buffer
//! holds, and each shaded event's kill reason is the counter that moved.

use std::path::PathBuf;

use sst1_board::watch::{Counted, PixelEvent};
use sst1_board::{AccuracyProfile, Board, BufferKind, Kill, Reference};
use sst1_trace::{execute, load_trace};

fn trace_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../traces/conformance/traces")
        .join(format!("{name}.trace.gz"))
}

/// The counter a kill reason moves (spec 5.31-5.35).
fn counter_of(kill: Option<Kill>) -> Counted {
    match kill {
        None => Counted::PixelsOut,
        Some(Kill::DepthFunc) => Counted::ZfuncFail,
        Some(Kill::Chroma) => Counted::ChromaFail,
        Some(Kill::AlphaMask | Kill::AlphaFunc) => Counted::AfuncFail,
        Some(Kill::Stipple | Kill::Clip) => Counted::Nothing,
    }
}

/// Replays `name` with `profile` twice, once on the fast path and once watching `(x,
/// y)`; checks the buffers and counters agree, and that the events explain the final
/// front, back and aux words at the pixel. Returns the events.
fn watched(name: &str, profile: AccuracyProfile, x: i32, y: i32) -> Vec<PixelEvent> {
    let trace = load_trace(&trace_path(name)).unwrap();
    let mut plain = Board::new(trace.board_config());
    plain.set_profile(profile);
    let plain_dumps = execute(&trace.ops, &mut plain, |_| {});
    let mut board = Board::new(trace.board_config());
    board.set_profile(profile);
    board.watch_pixel(x, y);
    let mut events = Vec::new();
    let mut dumps = Vec::new();
    for op in &trace.ops {
        dumps.extend(execute(std::slice::from_ref(op), &mut board, |_| {}));
        events.extend(board.take_pixel_events());
    }
    assert_eq!(board.pixel_events_dropped(), 0);
    assert!(dumps == plain_dumps, "{name}: the watch changed a dump");
    assert_eq!(board.stats(), plain.stats(), "{name}");
    for kind in [BufferKind::Front, BufferKind::Back, BufferKind::Aux] {
        assert!(board.dump_buffer(kind) == plain.dump_buffer(kind), "{name}");
        let Some(word) = board.buffer_word(kind, x, y) else {
            continue;
        };
        let (w, _) = board.display_size();
        let held = board.dump_buffer(kind)[(y as u32 * w + x as u32) as usize];
        if let Some(last) = events.iter().rev().find_map(|e| e.wrote(word)) {
            assert_eq!(last, held, "{name} {kind:?} ({x}, {y})");
        }
    }
    for e in &events {
        if let PixelEvent::Shaded(s) = e {
            assert_eq!(s.counted, counter_of(s.kill), "{name}: {s:?}");
            assert_eq!((s.x, s.row), (x, y));
        }
    }
    events
}

fn shaded(events: &[PixelEvent]) -> impl Iterator<Item = &sst1_board::watch::PixelStages> {
    events.iter().filter_map(|e| match e {
        PixelEvent::Shaded(s) => Some(&**s),
        _ => None,
    })
}

#[test]
fn untextured_and_textured_pixels() {
    let events = watched("gouraud_dither4", AccuracyProfile::HARDWARE, 300, 200);
    assert!(shaded(&events).count() >= 1);
    let events = watched("tex_2tmu_modulate", AccuracyProfile::HARDWARE, 100, 100);
    let last = shaded(&events).last().unwrap();
    assert_eq!(last.tmus.len(), 2);
    assert_eq!(Some(last.tmus[1].output), last.texel);
}

#[test]
fn fog_blend_and_depth_kill() {
    let events = watched("fog_table", AccuracyProfile::HARDWARE, 60, 60);
    assert!(shaded(&events).any(|s| s.fog.is_some_and(|f| f.enabled)));
    let events = watched("alpha_blend", AccuracyProfile::HARDWARE, 60, 20);
    assert!(shaded(&events).any(|s| s.blend.is_some()));
    let events = watched("depth_z", AccuracyProfile::HARDWARE, 60, 60);
    let killed: Vec<_> = shaded(&events).filter(|s| s.kill.is_some()).collect();
    assert_eq!(killed.len(), 1);
    assert_eq!(killed[0].kill, Some(Kill::DepthFunc));
    assert!(killed[0].depth.as_ref().is_some_and(|d| !d.pass));
}

#[test]
fn reference_models_and_lfb_writes() {
    for r in Reference::ALL {
        watched("tex_2tmu_modulate", r.profile(), 100, 100);
        watched("chroma_key", r.profile(), 320, 240);
    }
    let events = watched("lfb_writes", AccuracyProfile::HARDWARE, 20, 20);
    assert!(matches!(
        events[..],
        [PixelEvent::Fastfill { .. }, PixelEvent::LfbDirect { .. }]
    ));
    let events = watched("lfb_writes", AccuracyProfile::HARDWARE, 200, 200);
    let lfb: Vec<_> = shaded(&events).collect();
    assert_eq!(lfb.len(), 1);
    assert_eq!(lfb[0].source, sst1_board::watch::SourceKind::Lfb);
    assert!(lfb[0].tmus.is_empty() && lfb[0].texel.is_none());
}
