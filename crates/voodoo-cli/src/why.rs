//! `voodoo why TRACE X Y`: the history of one pixel (docs/pixel-history.md).
//!
//! The trace is replayed on a board that watches the pixel ([`Board::watch_pixel`]):
//! every operation that reaches it (triangle, fast fill, LFB write) leaves an event
//! with, for a shaded pixel, the value of every stage as the pipeline computed it. The
//! replay stops at the chosen dump (default: the last one; without dumps, the end of the
//! trace), and the history ends with the word that dump holds at the pixel, checked
//! against the last event that wrote it. With `--model vote` the history is taken on
//! each reference model's board and the stages are compared, event by event.

use std::collections::{BTreeMap, VecDeque};
use std::path::Path;

use serde::{Deserialize, Serialize};
use sst1_board::watch::{PixelEvent, PixelStages, StageColour, WordWrite};
use sst1_board::{AccuracyProfile, Board, Reference};
use sst1_regs::{addr, map, RegisterBus};
use sst1_trace::{open_trace, TraceOp};

/// The register-space writes kept per event as "written since the previous command"
/// (the newest; a triangle's setup is a few dozen).
const MAX_WRITES_SHOWN: usize = 96;

/// The most events a history keeps, the newest (each carries its state and setup, a
/// few KiB): a pixel a long trace redraws every frame has a bounded history.
pub const MAX_HISTORY: usize = 4096;

/// The largest frame-buffer coordinate (the LFB and the Y-origin flip address 10 bits).
const MAX_COORD: i32 = 1023;

/// A register write, as the history shows it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RegWrite {
    /// The op number of the write (1 is the trace's first op).
    pub op: u64,
    /// The chip it reached: `fbi` or `tmu0`..`tmu2`; in the writes since a command,
    /// every chip it reached, joined with `+`.
    pub chip: String,
    /// The register's spec name.
    pub name: String,
    /// The value written.
    pub value: u32,
}

/// What an operation was.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Operation {
    /// `triangleCMD` / `ftriangleCMD`: the board's `number`th triangle (from 1).
    Triangle { number: u64 },
    /// `fastfillCMD`: the board's `number`th fill (from 1).
    Fastfill { number: u64 },
    /// A write into the linear frame buffer (aperture offset and data).
    LfbWrite { addr: u32, value: u32 },
    /// Another write (a register write that reached the pixel some other way).
    Other,
}

/// One event in the history.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct OpEvent {
    /// The op number (1 is the trace's first op).
    pub op: u64,
    pub operation: Operation,
    /// The mode registers in force, each with the write that set it.
    pub state: Vec<RegWrite>,
    /// The register writes since the previous command (at most [`MAX_WRITES_SHOWN`], the
    /// newest), for a triangle its setup.
    pub written: Vec<RegWrite>,
    /// What happened to the pixel.
    pub event: PixelEvent,
}

/// The dump a history stops at, and the pixel's word in it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DumpPoint {
    /// Which dump (1 is the trace's first).
    pub number: u64,
    /// Its op number.
    pub op: u64,
    /// The buffer the dump names (`front`, `back`, `depth`, `aux`).
    pub buffer: String,
    pub file: String,
    pub width: u32,
    pub height: u32,
    /// The dump's value at the pixel; for a pixel outside the dump
    /// ([`Request::beyond_dump`]), the buffer word's value when the dump was taken.
    pub value: u16,
    /// The frame-buffer word index of the pixel in that buffer.
    pub word: Option<usize>,
    /// Whether the pixel lies inside the dump's rectangle.
    pub inside: bool,
}

/// The last event that wrote the word the dump reads.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct LastWrite {
    /// Index into [`History::events`].
    pub event: usize,
    pub op: u64,
    pub value: u16,
}

/// The history of one pixel on one model.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct History {
    pub trace: String,
    /// The model: `hardware`, `mame`, `dosbox-staging`, `86box`.
    pub model: String,
    pub x: i32,
    pub y: i32,
    /// The dump the history stops at; `None`: the trace has no dump and the history
    /// runs to its end.
    pub dump: Option<DumpPoint>,
    /// Dumps in the trace up to where the replay stopped.
    pub dumps_seen: u64,
    /// Ops run.
    pub ops_run: u64,
    pub events: Vec<OpEvent>,
    /// Older events left out (more than [`MAX_HISTORY`]).
    pub dropped: u64,
    /// The last event that wrote the dump's word at the pixel, if any.
    pub last_write: Option<LastWrite>,
}

/// What `voodoo why` was asked.
pub struct Request<'a> {
    pub trace: &'a Path,
    pub x: i32,
    pub y: i32,
    /// Dump number, from 1; `None`: the last.
    pub dump: Option<u64>,
    /// Follow a pixel outside the dump's rectangle (a row past its last or a column past
    /// its width) as the buffer's word at that column and row, which the dump does not
    /// show (`voodoo why --beyond-dump`).
    pub beyond_dump: bool,
}

/// The history of the pixel on a board with `profile` (model name `model`).
pub fn history(
    req: &Request<'_>,
    model: &str,
    profile: AccuracyProfile,
) -> Result<History, String> {
    if !(0..=MAX_COORD).contains(&req.x) || !(0..=MAX_COORD).contains(&req.y) {
        return Err(format!(
            "pixel ({}, {}) is outside the frame buffer's addresses (0..={MAX_COORD} each)",
            req.x, req.y
        ));
    }
    if req.dump == Some(0) {
        return Err("--dump counts from 1 (the trace's first dump)".into());
    }
    let stream = open_trace(req.trace).map_err(|e| e.to_string())?;
    let mut board = Board::new(stream.config());
    board.set_profile(profile);
    board.set_threads(1);
    board.watch_pixel(req.x, req.y);
    let mut regs = Registers::default();
    let mut events: VecDeque<OpEvent> = VecDeque::new();
    let mut dropped = 0u64;
    // Events at the last dump reached: (events recorded in all, the dump).
    let mut at_dump: Option<(u64, DumpPoint)> = None;
    let mut dumps_seen = 0u64;
    let mut last_size = (0, 0);
    let mut op_number = 0u64;
    for op in stream {
        let op = op.map_err(|e| e.to_string())?;
        op_number += 1;
        let before = board.stats();
        match &op {
            TraceOp::Config { .. } => {}
            TraceOp::Pci { offset, value } => board.pci_write(*offset, *value),
            TraceOp::Write { addr, value } => board.write32(*addr, *value),
            TraceOp::Read { addr, .. } => {
                board.read32(*addr);
            }
            TraceOp::Wait { cycles } => board.host_wait(*cycles),
            TraceOp::Dump { buffer, file } => {
                dumps_seen += 1;
                let (width, height) = board.display_size();
                last_size = (width, height);
                let data = board.dump_buffer(buffer.kind());
                let inside = (req.x as u32) < width && (req.y as u32) < height;
                let word = board.buffer_word(buffer.kind(), req.x, req.y);
                let value = if inside {
                    data[(req.y as u32 * width + req.x as u32) as usize]
                } else {
                    word.map_or(0, |i| board.fbi().fb.ram[i])
                };
                // Beyond the dump, a pixel is followed where its buffer has the word.
                let followed = inside || (req.beyond_dump && word.is_some());
                let point = DumpPoint {
                    number: dumps_seen,
                    op: op_number,
                    buffer: buffer.name().to_owned(),
                    file: file.clone(),
                    width,
                    height,
                    value,
                    word,
                    inside,
                };
                if req.dump == Some(dumps_seen) && !followed {
                    return Err(format!(
                        "pixel ({}, {}) is outside dump {dumps_seen} ({file}, {width}x{height})",
                        req.x, req.y
                    ));
                }
                at_dump = followed.then(|| (dropped + events.len() as u64, point));
                if req.dump == Some(dumps_seen) {
                    break;
                }
            }
        }
        let new = board.take_pixel_events();
        if !new.is_empty() {
            let after = board.stats();
            let operation = regs.operation(&op, &before, &after);
            for event in new {
                if events.len() == MAX_HISTORY {
                    events.pop_front();
                    dropped += 1;
                }
                events.push_back(OpEvent {
                    op: op_number,
                    operation: operation.clone(),
                    state: regs.state(board.config().tmus),
                    written: regs.since_command.iter().cloned().collect(),
                    event,
                });
            }
        }
        regs.after(&op, op_number);
    }
    if let Some(n) = req.dump {
        if n > dumps_seen {
            return Err(format!(
                "--dump {n}: {} has {dumps_seen} dump(s)",
                req.trace.display()
            ));
        }
    }
    let dump = match at_dump {
        Some((total, point)) => {
            // The events after the dump are not part of its history.
            let keep = total.saturating_sub(dropped) as usize;
            events.truncate(keep);
            Some(point)
        }
        None if dumps_seen > 0 => {
            return Err(format!(
                "pixel ({}, {}) is outside the last dump of {} ({}x{})",
                req.x,
                req.y,
                req.trace.display(),
                last_size.0,
                last_size.1
            ))
        }
        None => None,
    };
    let events: Vec<OpEvent> = events.into();
    let last_write = dump.as_ref().and_then(|d| {
        let word = d.word?;
        events.iter().enumerate().rev().find_map(|(i, e)| {
            e.event.wrote(word).map(|value| LastWrite {
                event: i,
                op: e.op,
                value,
            })
        })
    });
    Ok(History {
        trace: req.trace.display().to_string(),
        model: model.to_owned(),
        x: req.x,
        y: req.y,
        dump,
        dumps_seen,
        ops_run: op_number,
        events,
        dropped: dropped + board.pixel_events_dropped(),
        last_write,
    })
}

/// The register writes seen so far, for the state and setup an event shows.
#[derive(Default)]
struct Registers {
    /// (chip, normal-map offset) → the last write. Chip 0 is the FBI, 1..=3 TMU 0..2.
    last: BTreeMap<(u8, u32), RegWrite>,
    /// The writes since the last command, the newest [`MAX_WRITES_SHOWN`].
    since_command: VecDeque<RegWrite>,
}

/// The FBI registers an event's state shows, in register order.
const FBI_STATE: [u32; 13] = [
    addr::FBZ_COLOR_PATH,
    addr::FOG_MODE,
    addr::ALPHA_MODE,
    addr::FBZ_MODE,
    addr::LFB_MODE,
    addr::CLIP_LEFT_RIGHT,
    addr::CLIP_LOW_Y_HIGH_Y,
    addr::FOG_COLOR,
    addr::ZA_COLOR,
    addr::CHROMA_KEY,
    addr::STIPPLE,
    addr::COLOR0,
    addr::COLOR1,
];

/// The TMU registers an event's state shows.
const TMU_STATE: [u32; 4] = [
    addr::TEXTURE_MODE,
    addr::T_LOD,
    addr::T_DETAIL,
    addr::TEX_BASE_ADDR,
];

/// The name of chip `chip` (0 the FBI, 1..=3 TMU 0..2).
fn chip_name(chip: u8) -> String {
    match chip {
        0 => "fbi".to_owned(),
        n => format!("tmu{}", n - 1),
    }
}

impl Registers {
    /// The mode registers in force, FBI first, each TMU's after (TMUs on the board).
    fn state(&self, tmus: u32) -> Vec<RegWrite> {
        let fbi = FBI_STATE.iter().map(|&o| (0u8, o));
        let tmu = (1..=tmus.min(3) as u8).flat_map(|c| TMU_STATE.iter().map(move |&o| (c, o)));
        fbi.chain(tmu)
            .filter_map(|key| self.last.get(&key).cloned())
            .collect()
    }

    /// What op `op` was, from the counters before and after it.
    fn operation(
        &self,
        op: &TraceOp,
        before: &sst1_board::Stats,
        after: &sst1_board::Stats,
    ) -> Operation {
        match *op {
            TraceOp::Write { addr, value } if (0x40_0000..0x80_0000).contains(&addr) => {
                Operation::LfbWrite { addr, value }
            }
            _ if after.triangles != before.triangles => Operation::Triangle {
                number: after.triangles,
            },
            _ if after.fastfills != before.fastfills => Operation::Fastfill {
                number: after.fastfills,
            },
            _ => Operation::Other,
        }
    }

    /// Note op `op` (number `number`) after it has run.
    fn after(&mut self, op: &TraceOp, number: u64) {
        let TraceOp::Write { addr, value } = *op else {
            return;
        };
        if addr >= 0x40_0000 {
            return;
        }
        let mut offset = addr & 0x3fc;
        // fbiInit3 bit 0 with address bit 21: the alternate triangle map (spec 5).
        let remap = self
            .last
            .get(&(0, addr::FBI_INIT3))
            .is_some_and(|w| w.value & 1 != 0);
        if remap && addr & 0x20_0000 != 0 {
            offset = map::remap_offset(offset);
        }
        let Some(desc) = map::desc_of(offset) else {
            return;
        };
        let mut chips = (addr >> 10) & 0xf;
        if chips == 0 {
            chips = 0xf;
        }
        let fbi = chips & 1 != 0 && desc.chips.contains(map::Chips::FBI);
        let tmus =
            (0..3u8).filter(|i| chips & (2 << i) != 0 && desc.chips.contains(map::Chips::TREX));
        let targets: Vec<u8> = fbi
            .then_some(0)
            .into_iter()
            .chain(tmus.map(|i| i + 1))
            .collect();
        let is_command = fbi
            && matches!(
                offset,
                addr::TRIANGLE_CMD
                    | addr::F_TRIANGLE_CMD
                    | addr::FASTFILL_CMD
                    | addr::SWAPBUFFER_CMD
            );
        if is_command {
            self.since_command.clear();
            return;
        }
        if targets.is_empty() {
            return;
        }
        let write = |chip: String| RegWrite {
            op: number,
            chip,
            name: desc.name.to_owned(),
            value,
        };
        let all: Vec<String> = targets.iter().map(|&c| chip_name(c)).collect();
        if self.since_command.len() == MAX_WRITES_SHOWN {
            self.since_command.pop_front();
        }
        self.since_command.push_back(write(all.join("+")));
        for chip in targets {
            self.last.insert((chip, offset), write(chip_name(chip)));
        }
    }
}

/// A colour as `(r, g, b, a)`.
fn colour(c: &StageColour) -> String {
    format!("({:3}, {:3}, {:3}, {:3})", c.r, c.g, c.b, c.a)
}

/// A word write as `0xVALUE at word 0xINDEX`.
fn word(w: &Option<WordWrite>) -> String {
    match w {
        Some(w) => format!("{:#06x} at word {:#x}", w.value, w.index),
        None => "none".to_owned(),
    }
}

/// The stages of a shaded pixel as `(label, value)` lines, in pipeline order.
fn pixel_lines(s: &PixelStages) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut line = |label: &str, value: String| out.push((label.to_owned(), value));
    if let Some(it) = &s.iterated {
        let [r, g, b, a] = it.rgba_12_12;
        line(
            "iterated",
            format!(
                "rgba 12.12 {r:#x} {g:#x} {b:#x} {a:#x} -> {}",
                colour(&it.colour)
            ),
        );
        line(
            "z/w",
            format!(
                "z 20.12 {:#x} (z16 {:#06x}), w 32.32 {:#x} (wfloat {:#06x}); depth value {:#x}",
                it.z_20_12, it.z16, it.w_32_32, it.wfloat, it.depth_value
            ),
        );
    }
    if let Some(d) = &s.depth {
        let dest = d
            .dest
            .map_or("no aux buffer".to_owned(), |v| format!("{v:#06x}"));
        let verdict = if d.pass { "pass" } else { "fail" };
        line(
            "depth",
            format!(
                "{}: source {:#06x} against {dest}: {verdict}",
                d.function, d.source
            ),
        );
    }
    for t in &s.tmus {
        line(
            &format!("tmu{}", t.tmu),
            format!(
                "s {:#x} t {:#x} w {:#x} (.32), lod 8.8 {:#x} frac {}; texel {} -> out {}",
                t.s_32,
                t.t_32,
                t.w_32,
                t.lod_8_8,
                t.lod_fraction,
                colour(&t.texel),
                colour(&t.output)
            ),
        );
    }
    if let Some(t) = &s.texel {
        line("texel", colour(t));
    }
    if let Some(c) = &s.colour {
        line("other", colour(&c.other));
        line("local", colour(&c.local));
        if let Some(combined) = &c.combined {
            line("combine", colour(combined));
        }
    }
    if let Some(f) = &s.fog {
        let on = if f.enabled { "on" } else { "off" };
        line("fog", format!("{on} -> {}", colour(&f.output)));
    }
    if let Some(b) = &s.blend {
        let aux = b.dst_aux.map_or("none".to_owned(), |v| format!("{v:#06x}"));
        line(
            "blend",
            format!(
                "src {} prefog {} dst {:#06x} dst aux {aux} dither entry {} -> {}",
                colour(&b.src),
                colour(&b.prefog),
                b.dst_rgb565,
                b.dither_value,
                colour(&b.output)
            ),
        );
    }
    if let Some(w) = &s.write {
        line(
            "dither",
            format!(
                "{:?} entry {}: {} -> {}",
                w.dither,
                w.dither_value,
                colour(&w.colour),
                word(&w.colour_word)
            ),
        );
        line("aux", word(&w.aux_word));
    }
    let fate = match s.kill {
        None => "written".to_owned(),
        Some(k) => format!("killed: {k:?}"),
    };
    line("fate", format!("{fate} (counted: {:?})", s.counted));
    out
}

/// The stage lines of any event.
pub fn event_lines(e: &PixelEvent) -> Vec<(String, String)> {
    match e {
        PixelEvent::Shaded(s) => pixel_lines(s),
        PixelEvent::Clipped { source } => vec![(
            "fate".to_owned(),
            format!("killed: Clip ({source:?} outside the clip rectangle)"),
        )],
        PixelEvent::Fastfill {
            colour_word,
            aux_word,
        } => vec![
            ("fill".to_owned(), word(colour_word)),
            ("aux".to_owned(), word(aux_word)),
        ],
        PixelEvent::LfbDirect {
            colour_word,
            aux_word,
        } => vec![
            ("lfb".to_owned(), word(colour_word)),
            ("aux".to_owned(), word(aux_word)),
        ],
    }
}

/// Width of the label column.
const LABEL: usize = 10;

/// The heading of an event's block.
fn heading(e: &OpEvent) -> String {
    let what = match &e.operation {
        Operation::Triangle { number } => format!("triangle {number}"),
        Operation::Fastfill { number } => format!("fast fill {number}"),
        Operation::LfbWrite { addr, value } => format!("LFB write {value:#010x} at {addr:#x}"),
        Operation::Other => "write".to_owned(),
    };
    let kind = match &e.event {
        PixelEvent::Shaded(s) => format!(" ({:?} through the pipeline)", s.source),
        PixelEvent::Clipped { .. } => " (clipped)".to_owned(),
        PixelEvent::Fastfill { .. } => String::new(),
        PixelEvent::LfbDirect { .. } => " (bypassing the pipeline)".to_owned(),
    };
    format!("op {}: {what}{kind}", e.op)
}

/// The history in words.
pub fn render(h: &History) -> String {
    let mut out = String::new();
    let at = match &h.dump {
        Some(d) => format!(
            "up to dump {} (op {}, {} buffer, {})",
            d.number, d.op, d.buffer, d.file
        ),
        None => format!("to the end ({} ops, no dump)", h.ops_run),
    };
    out += &format!(
        "pixel ({}, {}) of {}, model {}, {at}: {} event(s)",
        h.x,
        h.y,
        h.trace,
        h.model,
        h.events.len()
    );
    if h.dropped > 0 {
        out += &format!(", {} older ones left out", h.dropped);
    }
    out += "\n";
    for e in &h.events {
        out += &format!("\n{}\n", heading(e));
        for r in &e.state {
            out += &format!(
                "  {:LABEL$} {:4} {:<14} = {:#010x}  (op {})\n",
                "state", r.chip, r.name, r.value, r.op
            );
        }
        if !e.written.is_empty() {
            let list: Vec<String> = e
                .written
                .iter()
                .map(|w| format!("{}={:#x}", w.name, w.value))
                .collect();
            for chunk in list.chunks(6) {
                out += &format!("  {:LABEL$} {}\n", "written", chunk.join(" "));
            }
        }
        for (label, value) in event_lines(&e.event) {
            out += &format!("  {label:LABEL$} {value}\n");
        }
    }
    if let Some(d) = &h.dump {
        out += &if d.inside {
            format!(
                "\ndump {} holds {:#06x} at ({}, {})",
                d.number, d.value, h.x, h.y
            )
        } else {
            format!(
                "\ndump {} ({}x{}) does not show ({}, {}); the buffer's word there held {:#06x}",
                d.number, d.width, d.height, h.x, h.y, d.value
            )
        };
        match &h.last_write {
            Some(w) if w.value == d.value => {
                out += &format!(", written by op {} (the history agrees)\n", w.op)
            }
            Some(w) => {
                out += &format!(
                    "; the history's last write, by op {}, was {:#06x} (it disagrees)\n",
                    w.op, w.value
                )
            }
            None => out += ", never written in this history\n",
        }
    }
    out
}

/// Where the references part ways at one event.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Divergence {
    /// The op number.
    pub op: u64,
    /// The first stage whose values differ (`"event"`: not every model has it).
    pub stage: String,
    /// Each model's value at that stage (`None`: no event or no such stage).
    pub values: Vec<(String, Option<String>)>,
}

/// The histories of the three reference models and where they part ways.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Comparison {
    pub histories: Vec<History>,
    pub divergences: Vec<Divergence>,
}

/// Each history's events grouped by op: op → (model index → that op's events).
fn by_op(histories: &[History]) -> BTreeMap<(u64, usize), Vec<Option<&OpEvent>>> {
    let mut map: BTreeMap<(u64, usize), Vec<Option<&OpEvent>>> = BTreeMap::new();
    for (m, h) in histories.iter().enumerate() {
        let mut nth: BTreeMap<u64, usize> = BTreeMap::new();
        for e in &h.events {
            let k = nth.entry(e.op).or_default();
            let slot = map
                .entry((e.op, *k))
                .or_insert_with(|| vec![None; histories.len()]);
            slot[m] = Some(e);
            *k += 1;
        }
    }
    map
}

/// Compare histories stage by stage, event by event (events paired by op).
pub fn compare(histories: Vec<History>) -> Comparison {
    let mut divergences = Vec::new();
    for ((op, _), events) in by_op(&histories) {
        let names = histories.iter().map(|h| h.model.clone());
        if events.iter().any(Option::is_none) {
            let values = names
                .zip(&events)
                .map(|(n, e)| (n, e.map(heading)))
                .collect();
            divergences.push(Divergence {
                op,
                stage: "event".to_owned(),
                values,
            });
            continue;
        }
        let lines: Vec<Vec<(String, String)>> = events
            .iter()
            .flatten()
            .map(|e| event_lines(&e.event))
            .collect();
        let longest = lines.iter().map(Vec::len).max().unwrap_or(0);
        for i in 0..longest {
            let at: Vec<Option<&(String, String)>> = lines.iter().map(|l| l.get(i)).collect();
            if at.windows(2).all(|w| w[0] == w[1]) {
                continue;
            }
            let stage = at
                .iter()
                .flatten()
                .next()
                .map_or(String::new(), |(l, _)| l.clone());
            let values = names
                .zip(&at)
                .map(|(n, l)| (n, l.map(|(label, v)| format!("{label} {v}"))))
                .collect();
            divergences.push(Divergence { op, stage, values });
            break;
        }
    }
    Comparison {
        histories,
        divergences,
    }
}

/// A comparison in words: each model's history, then where they part.
pub fn render_comparison(c: &Comparison) -> String {
    let mut out = String::new();
    for h in &c.histories {
        out += &render(h);
        out += "\n";
    }
    if c.divergences.is_empty() {
        out += "the references agree at every stage of every event\n";
        return out;
    }
    out += "where the references part ways:\n";
    for d in &c.divergences {
        out += &format!("\nop {}: first difference at {}\n", d.op, d.stage);
        for (model, value) in &d.values {
            let v = value.as_deref().unwrap_or("(none)");
            out += &format!("  {model:14} {v}\n");
        }
    }
    out
}

/// The reference models, with their names, for `--model vote`.
pub fn references() -> Vec<(&'static str, AccuracyProfile)> {
    Reference::ALL
        .iter()
        .map(|r| (r.golden_dir(), r.profile()))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fill and one flat triangle over pixel (40, 40), then a dump.
    const TRACE: &str = "pci 0x40 0x3\n\
        w 0x000210 0x7\nw 0x000214 0x1a2\nw 0x000210 0x1\nw 0x000220 0x02c00060\n\
        w 0x000224 0x020b0002\nw 0x000208 0x00120032\nw 0x00020c 0x01e0027f\n\
        w 0x000218 0x1874b040\nw 0x00021c 0x77de4000\nw 0x000200 0x1\n\
        w 0x000214 0x002000a2\nw 0x000118 0x280\nw 0x00011c 0x1e0\n\
        w 0x000148 0x0\nw 0x000130 0xffff\nw 0x000110 0x631\nw 0x000124 0x0\n\
        w 0x000008 0x140\nw 0x00000c 0xa0\nw 0x000010 0x640\nw 0x000014 0x140\n\
        w 0x000018 0x280\nw 0x00001c 0x640\nw 0x000020 0x64000\nw 0x000024 0x32000\n\
        w 0x000028 0xc8000\nw 0x00002c 0x1234000\nw 0x000030 0xff000\nw 0x000080 0x0\n\
        dump front t_front.raw\n";

    fn history_of(name: &str, trace: &str, x: i32, y: i32) -> Result<History, String> {
        let path = std::env::temp_dir().join(format!("why-{name}-{}.trace", std::process::id()));
        std::fs::write(&path, trace).unwrap();
        let req = Request {
            trace: &path,
            x,
            y,
            dump: None,
            beyond_dump: false,
        };
        let h = history(&req, "hardware", AccuracyProfile::HARDWARE);
        std::fs::remove_file(&path).unwrap();
        h
    }

    #[test]
    fn json_round_trip_gives_the_same_history() {
        let h = history_of("json", TRACE, 40, 40).unwrap();
        assert_eq!(h.events.len(), 2);
        assert_eq!(h.last_write.as_ref().map(|w| w.value), Some(0x6199));
        let json = serde_json::to_string(&h).unwrap();
        let back: History = serde_json::from_str(&json).unwrap();
        assert_eq!(back, h);
        let c = compare(vec![h.clone(), h]);
        assert!(c.divergences.is_empty());
        let back: Comparison = serde_json::from_str(&serde_json::to_string(&c).unwrap()).unwrap();
        assert_eq!(back, c);
    }

    #[test]
    fn comparison_names_the_first_stage_that_differs() {
        let h = history_of("cmp", TRACE, 40, 40).unwrap();
        let mut other = h.clone();
        other.model = "changed".into();
        let PixelEvent::Shaded(s) = &mut other.events[1].event else {
            panic!("event 1 is the triangle");
        };
        s.fog.as_mut().unwrap().output.r ^= 1;
        s.write.as_mut().unwrap().colour.r ^= 1;
        let c = compare(vec![h, other]);
        assert_eq!(c.divergences.len(), 1);
        let d = &c.divergences[0];
        assert_eq!((d.op, d.stage.as_str()), (30, "fog"));
        assert_eq!(
            d.values[0].1.as_deref(),
            Some("fog off -> (100,  50, 200, 255)")
        );
        assert_eq!(
            d.values[1].1.as_deref(),
            Some("fog off -> (101,  50, 200, 255)")
        );
    }

    #[test]
    fn a_long_history_keeps_the_newest_events() {
        // A 1x1 clip rectangle at (0, 0) and more fills of it than a history keeps.
        let init = TRACE.split("w 0x000148").next().unwrap();
        let mut trace = format!("{init}w 0x000118 0x1\nw 0x00011c 0x1\nw 0x000110 0x200\n");
        let fills = MAX_HISTORY + 5;
        for i in 0..fills {
            trace += &format!("w 0x000148 {i:#x}\nw 0x000124 0x0\n");
        }
        trace += "dump front f.raw\n";
        let h = history_of("long", &trace, 0, 0).unwrap();
        assert_eq!((h.events.len(), h.dropped), (MAX_HISTORY, 5));
        let last = h.events.last().unwrap();
        assert_eq!(
            last.operation,
            Operation::Fastfill {
                number: fills as u64
            }
        );
        // color1 = 0x1003 (the last fill's number) as RGB565, undithered.
        let c = (fills - 1) as u32;
        let rgb565 = ((c >> 19 & 0x1f) << 11 | (c >> 10 & 0x3f) << 5 | (c >> 3 & 0x1f)) as u16;
        assert_eq!(h.dump.as_ref().map(|d| d.value), Some(rgb565));
        assert_eq!(h.last_write.map(|w| w.value), Some(rgb565));
    }

    #[test]
    fn a_clipped_pixel_is_killed_by_the_clip_rectangle() {
        // The triangle covers (40, 40); a clip rectangle of columns 0..30 leaves it out.
        let trace = TRACE.replace("w 0x000008 0x140", "w 0x000118 0x1e\nw 0x000008 0x140");
        let h = history_of("clip", &trace, 40, 40).unwrap();
        assert_eq!(h.events.len(), 2);
        assert_eq!(h.events[1].operation, Operation::Triangle { number: 1 });
        assert_eq!(
            h.events[1].event,
            PixelEvent::Clipped {
                source: sst1_board::watch::SourceKind::Triangle
            }
        );
        assert_eq!(h.last_write.map(|w| w.op), Some(18));
        // Inside the rectangle, the same triangle shades the pixel.
        let h = history_of("inside", &trace, 29, 40).unwrap();
        assert!(matches!(h.events[1].event, PixelEvent::Shaded(_)));
    }

    #[test]
    fn a_trace_without_dumps_runs_to_its_end() {
        let trace = TRACE.replace("dump front t_front.raw\n", "");
        let h = history_of("nodump", &trace, 40, 40).unwrap();
        assert!(h.dump.is_none() && h.last_write.is_none());
        assert_eq!(h.events.len(), 2);
        assert_eq!(h.ops_run, 30);
        // A pixel outside the triangle: the fill alone.
        let h = history_of("fill", TRACE, 600, 400).unwrap();
        assert_eq!(h.events.len(), 1);
        assert_eq!(h.events[0].operation, Operation::Fastfill { number: 1 });
        assert_eq!(h.last_write.map(|w| (w.op, w.value)), Some((18, 0)));
        assert_eq!(h.dump.map(|d| d.value), Some(0));
    }
}
