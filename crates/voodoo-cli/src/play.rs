//! `voodoo play`: a trace stepped by frame or by drawing command in a window.
//!
//! [`Player`] is the logic, apart from any window so tests can drive it: it runs the
//! trace on one board per model (the hardware model and each reference emulator's, in
//! lock step), stops at frame ends (after a `swapbufferCMD` or a `dump` and the dumps
//! right after it) or after each drawing command (`triangleCMD`, `ftriangleCMD`,
//! `fastfillCMD`, `swapbufferCMD`, or a dump), goes back by replaying from the start,
//! and renders the chosen buffer (front, back or depth) of the chosen model (hardware,
//! the vote of the three references, or one reference) as 0x00RRGGBB pixels, with the
//! pixels that break the conformance pass rule against golden dumps marked.
//! [`run`] puts it in an `sst1-window` window, the keys listed in the title bar.

use sst1_board::{Board, BoardConfig, BufferKind, Reference};
use sst1_regs::RegisterBus;
use sst1_trace::judge::{self, Rule};
use sst1_trace::{vote_buffer, OpCounts, TraceOp};
use std::path::{Path, PathBuf};

/// Which model's buffers are shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// The hardware model (the default accuracy profile).
    Hardware,
    /// The three references voted pixel by pixel (two of three, MAME's where all differ).
    Vote,
    /// One reference emulator's model.
    Reference(Reference),
}

impl View {
    /// Every view, in the order the `M` key cycles through them.
    pub const ALL: [View; 5] = [
        View::Hardware,
        View::Vote,
        View::Reference(Reference::Mame),
        View::Reference(Reference::DosboxStaging),
        View::Reference(Reference::Box86),
    ];

    /// The name `--model` gives it.
    pub fn name(self) -> &'static str {
        match self {
            View::Hardware => "hardware",
            View::Vote => "vote",
            View::Reference(r) => r.golden_dir(),
        }
    }
}

/// Which buffer is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shown {
    Front,
    Back,
    /// The aux buffer, as grey levels (its high byte).
    Depth,
}

impl Shown {
    fn kind(self) -> BufferKind {
        match self {
            Shown::Front => BufferKind::Front,
            Shown::Back => BufferKind::Back,
            Shown::Depth => BufferKind::Aux,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Shown::Front => "front",
            Shown::Back => "back",
            Shown::Depth => "depth",
        }
    }
}

/// The colour of a pixel that breaks a consensus of the goldens.
pub const CONSENSUS_FAIL: u32 = 0x00ff_0000;
/// The colour of a pixel that breaks a majority of the goldens.
pub const MAJORITY_FAIL: u32 = 0x00ff_ff00;

/// The goldens of one dump: the rule of every pixel.
struct Golden {
    /// The dump's file name in the trace.
    file: String,
    buffer: BufferKind,
    rules: Vec<Rule>,
}

/// What a key asks of the player.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    NextFrame,
    NextCommand,
    PreviousFrame,
    PreviousCommand,
    Restart,
    Show(Shown),
    NextModel,
    ToggleDiff,
    /// Show or hide the keys and the status drawn over the picture.
    ToggleHelp,
    Quit,
}

impl Action {
    /// The action of a key, if it has one.
    pub fn of(key: &sst1_window::Key) -> Option<Action> {
        use sst1_window::Key;
        Some(match key {
            Key::Right | Key::Space | Key::PageDown => Action::NextFrame,
            Key::Down | Key::Char('n') => Action::NextCommand,
            Key::Left | Key::PageUp => Action::PreviousFrame,
            Key::Up | Key::Char('p') => Action::PreviousCommand,
            Key::Home => Action::Restart,
            Key::Char('f') => Action::Show(Shown::Front),
            Key::Char('b') => Action::Show(Shown::Back),
            Key::Char('d') => Action::Show(Shown::Depth),
            Key::Char('m') | Key::Tab => Action::NextModel,
            Key::Char('g') => Action::ToggleDiff,
            Key::Char('h') | Key::Char('?') => Action::ToggleHelp,
            Key::Escape | Key::Char('q') => Action::Quit,
            _ => return None,
        })
    }
}

/// The keys, as the title bar lists them.
pub const KEYS: &str =
    "H: keys on screen, Right/Space: next frame, Down/N: next command, Left: previous frame, \
                        Up/P: previous command, Home: start, F/B/D: front/back/depth, \
                        M: model, G: golden diff, Q: quit";

/// A trace being played.
pub struct Player {
    ops: Vec<TraceOp>,
    config: BoardConfig,
    /// The hardware model's board.
    hardware: Board,
    /// Each reference's board, in [`Reference::ALL`] order.
    references: [Board; 3],
    /// Ops run so far.
    pos: usize,
    /// The position after each frame end, ascending.
    frame_ends: Vec<usize>,
    /// The position after each drawing command or dump, ascending.
    command_ends: Vec<usize>,
    view: View,
    shown: Shown,
    diff: bool,
    /// The keys and status drawn over the picture (`H`).
    help: bool,
    goldens: Option<PathBuf>,
    /// The goldens of the last dump passed of the colour buffers and of the aux buffer.
    golden: Vec<Golden>,
}

/// Where the frames and the drawing commands of `ops` end: the positions after each
/// (a frame ends with a swap, or a dump not right after a swap or dump, and takes in
/// the dumps right after it; a drawing command is a triangle, fast fill, swap or dump).
fn ends(ops: &[TraceOp]) -> (Vec<usize>, Vec<usize>) {
    let (mut frames, mut commands) = (Vec::new(), Vec::new());
    let mut counts = OpCounts::default();
    let mut after_end = false;
    for (i, op) in ops.iter().enumerate() {
        let before = (counts.triangles, counts.fastfills, counts.swaps);
        counts.add(op);
        let swap = counts.swaps != before.2;
        let dump = matches!(op, TraceOp::Dump { .. });
        if swap || dump || (counts.triangles, counts.fastfills) != (before.0, before.1) {
            commands.push(i + 1);
        }
        if swap || (dump && !after_end) {
            frames.push(i + 1);
        } else if dump {
            // A dump right after a frame end belongs to that frame.
            if let Some(last) = frames.last_mut() {
                *last = i + 1;
            }
        }
        after_end = swap || dump;
    }
    (frames, commands)
}

impl Player {
    /// A player at the start of `ops`, on boards of `config`, showing `view`'s front
    /// buffer; `goldens` is a folder of golden dumps (`check`'s layout: one folder per
    /// reference, or the dumps themselves).
    pub fn new(
        ops: Vec<TraceOp>,
        config: BoardConfig,
        view: View,
        goldens: Option<PathBuf>,
    ) -> Self {
        let diff = goldens.is_some();
        let (frame_ends, command_ends) = ends(&ops);
        Self {
            ops,
            config,
            hardware: Board::new(config),
            references: Reference::ALL.map(|r| board_of(config, r)),
            pos: 0,
            frame_ends,
            command_ends,
            view,
            shown: Shown::Front,
            diff,
            help: false,
            goldens,
            golden: Vec::new(),
        }
    }

    /// Ops run so far, and the trace's length.
    #[cfg(test)]
    pub fn position(&self) -> (usize, usize) {
        (self.pos, self.ops.len())
    }

    /// Frames ended so far.
    pub fn frame_number(&self) -> usize {
        self.frame_ends.partition_point(|&e| e <= self.pos)
    }

    #[cfg(test)]
    pub fn view(&self) -> View {
        self.view
    }

    #[cfg(test)]
    pub fn shown(&self) -> Shown {
        self.shown
    }

    /// Does what `action` asks; `false` for [`Action::Quit`].
    pub fn act(&mut self, action: Action) -> bool {
        let next = |ends: &[usize], pos: usize| {
            ends.get(ends.partition_point(|&e| e <= pos))
                .copied()
                .unwrap_or(pos)
        };
        let previous = |ends: &[usize], pos: usize| {
            ends[..ends.partition_point(|&e| e < pos)]
                .last()
                .copied()
                .unwrap_or(0)
        };
        match action {
            Action::NextFrame => self.seek(next(&self.frame_ends, self.pos)),
            Action::NextCommand => self.seek(next(&self.command_ends, self.pos)),
            Action::PreviousFrame => self.seek(previous(&self.frame_ends, self.pos)),
            Action::PreviousCommand => self.seek(previous(&self.command_ends, self.pos)),
            Action::Restart => self.seek(0),
            Action::Show(shown) => self.shown = shown,
            Action::NextModel => {
                let at = View::ALL.iter().position(|&v| v == self.view).unwrap_or(0);
                self.view = View::ALL[(at + 1) % View::ALL.len()];
            }
            Action::ToggleDiff => self.diff = !self.diff,
            Action::ToggleHelp => self.help = !self.help,
            Action::Quit => return false,
        }
        true
    }

    /// Runs one op on every board.
    fn run_op(&mut self) {
        let op = &self.ops[self.pos];
        self.pos += 1;
        let boards = std::iter::once(&mut self.hardware).chain(self.references.iter_mut());
        match op {
            TraceOp::Config { .. } => {}
            TraceOp::Pci { offset, value } => boards.for_each(|b| b.pci_write(*offset, *value)),
            TraceOp::Write { addr, value } => boards.for_each(|b| b.write32(*addr, *value)),
            TraceOp::Read { addr, .. } => boards.for_each(|b| {
                b.read32(*addr);
            }),
            TraceOp::Wait { cycles } => boards.for_each(|b| b.host_wait(*cycles)),
            TraceOp::Dump { buffer, file } => {
                let (kind, file) = (buffer.kind(), file.clone());
                self.load_golden(kind, file);
            }
        }
    }

    /// Runs on to op `to`, or replays from the start on fresh boards to go back.
    fn seek(&mut self, to: usize) {
        let to = to.min(self.ops.len());
        if to < self.pos {
            self.hardware = Board::new(self.config);
            self.references = Reference::ALL.map(|r| board_of(self.config, r));
            self.pos = 0;
            self.golden.clear();
        }
        while self.pos < to {
            self.run_op();
        }
    }

    /// Loads the goldens of dump `file` of buffer `kind`, replacing that buffer's.
    fn load_golden(&mut self, kind: BufferKind, file: String) {
        let aux = kind == BufferKind::Aux;
        self.golden.retain(|g| (g.buffer == BufferKind::Aux) != aux);
        let Some(dir) = &self.goldens else {
            return;
        };
        if let Some(rules) = golden_rules(dir, &file) {
            self.golden.push(Golden {
                file,
                buffer: kind,
                rules,
            });
        }
    }

    /// The shown buffer of the shown model, raw.
    pub fn buffer(&self) -> (usize, usize, Vec<u16>) {
        let kind = self.shown.kind();
        let (w, h) = self.hardware.display_size();
        let pixels = match self.view {
            View::Hardware => self.hardware.dump_buffer(kind),
            View::Vote => vote_buffer(&self.references, kind),
            View::Reference(r) => {
                let at = Reference::ALL.iter().position(|&x| x == r).unwrap_or(0);
                self.references[at].dump_buffer(kind)
            }
        };
        (w as usize, h as usize, pixels)
    }

    /// The goldens that apply to the shown buffer: the last dump passed of it (front
    /// and back dumps both judge the colour buffers).
    fn golden_for_shown(&self) -> Option<&Golden> {
        let aux = self.shown == Shown::Depth;
        self.golden
            .iter()
            .find(|g| (g.buffer == BufferKind::Aux) == aux)
    }

    /// What the window shows: the shown buffer as 0x00RRGGBB (colour by bit
    /// replication, depth as the grey of its high byte); with the diff on and goldens for
    /// it, every pixel breaking a consensus [`CONSENSUS_FAIL`], a majority
    /// [`MAJORITY_FAIL`], the rest at half brightness. Also the count of failing pixels.
    pub fn render(&self) -> (sst1_window::Frame, Option<u64>) {
        let (w, h, raw) = self.buffer();
        let mut pixels: Vec<u32> = match self.shown {
            Shown::Depth => raw
                .iter()
                .map(|&d| u32::from(d >> 8) * 0x0001_0101)
                .collect(),
            _ => raw.iter().map(|&p| sst1_window::xrgb(p)).collect(),
        };
        let mut failing = None;
        if let (true, Some(golden)) = (self.diff, self.golden_for_shown()) {
            let mut n = 0;
            for (i, px) in pixels.iter_mut().enumerate() {
                let rule = golden.rules.get(i).copied();
                let value = raw[i];
                *px = match rule {
                    Some(r @ Rule::Consensus(_)) if r.broken_by(value) => CONSENSUS_FAIL,
                    Some(r @ Rule::Majority(_)) if r.broken_by(value) => MAJORITY_FAIL,
                    _ => (*px >> 1) & 0x007f_7f7f,
                };
                if matches!(*px, CONSENSUS_FAIL | MAJORITY_FAIL) {
                    n += 1;
                }
            }
            failing = Some(n);
        }
        let mut frame = sst1_window::Frame {
            width: w,
            height: h,
            pixels,
        };
        if self.help {
            use sst1_window::text;
            let columns = text::columns(w);
            let mut lines = text::wrap(&self.status(failing), columns);
            lines.extend(text::wrap(KEYS, columns));
            text::draw_lines(&mut frame, &lines);
        }
        (frame, failing)
    }

    /// Where the player is and what it shows, in one line.
    fn status(&self, failing: Option<u64>) -> String {
        let diff = match (self.diff, failing, self.golden_for_shown()) {
            (false, ..) => String::new(),
            (true, Some(n), Some(g)) => format!(", {n} pixels off {}", g.file),
            (true, ..) => ", no goldens".to_string(),
        };
        format!(
            "frame {}, op {}/{}, {} {}{diff}",
            self.frame_number(),
            self.pos,
            self.ops.len(),
            self.view.name(),
            self.shown.name(),
        )
    }

    /// The title bar: where the player is, what it shows, and the keys.
    pub fn title(&self, name: &str, failing: Option<u64>) -> String {
        format!("voodoo play {name}: {} | {KEYS}", self.status(failing))
    }
}

fn board_of(config: BoardConfig, r: Reference) -> Board {
    let mut b = Board::new(config);
    b.set_profile(r.profile());
    b
}

/// The rule of every pixel of dump `file` from the goldens in `dir`: one folder per
/// reference (`check`'s layout) judged by the pass rule, or else the dump itself in
/// `dir`, which every pixel must equal. `None` where there are none.
fn golden_rules(dir: &Path, file: &str) -> Option<Vec<Rule>> {
    let stem = file.strip_suffix(".raw").unwrap_or(file);
    let find = |dir: &Path| {
        [format!("{stem}.raw.gz"), format!("{stem}.raw")]
            .iter()
            .find_map(|f| judge::load_golden(&dir.join(f)))
    };
    let found: Vec<Vec<u16>> = Reference::ALL
        .iter()
        .filter_map(|r| find(&dir.join(r.golden_dir())))
        .collect();
    if found.len() >= 2 {
        let buffers: Vec<&[u16]> = found.iter().map(Vec::as_slice).collect();
        // The rules do not depend on ours.
        return Some(judge::judge(&buffers, &[]).rules);
    }
    let single = find(dir).or_else(|| found.into_iter().next())?;
    Some(single.into_iter().map(Rule::Consensus).collect())
}

/// `voodoo play`: the window and its keys around a [`Player`].
pub fn run(trace: &Path, view: View, goldens: Option<PathBuf>) -> Result<(), String> {
    use sst1_window::{Event, Window};
    let loaded = sst1_trace::load_trace(trace).map_err(|e| e.to_string())?;
    if let Some(dir) = &goldens {
        if !std::fs::metadata(dir)
            .map_err(|e| format!("goldens folder {}: {e}", dir.display()))?
            .is_dir()
        {
            return Err(format!("goldens folder {}: not a folder", dir.display()));
        }
    }
    let config = loaded.board_config();
    let name = trace.file_name().map_or_else(
        || trace.display().to_string(),
        |n| n.to_string_lossy().into(),
    );
    let mut player = Player::new(loaded.ops, config, view, goldens);
    let window = Window::open(&format!("voodoo play {name}"))
        .map_err(|why| format!("play needs a window: {why}"))?;
    player.act(Action::NextFrame);
    let show = |player: &Player| {
        let (frame, failing) = player.render();
        window.set_title(&player.title(&name, failing));
        window.show(frame);
    };
    show(&player);
    loop {
        match window.next_event() {
            Some(Event::Key(key)) => {
                if let Some(action) = Action::of(&key) {
                    if !player.act(action) {
                        return Ok(());
                    }
                    show(&player);
                }
            }
            Some(Event::Captured(Err(e))) => return Err(format!("VOODOO_WINDOW_CAPTURE: {e}")),
            // `VOODOO_WINDOW_CAPTURE` has the first frame: done.
            Some(Event::Captured(Ok(()))) | Some(Event::Closed) | None => return Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sst1_trace::{execute, load_trace, DumpBuffer};

    fn repo(path: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../..")
            .join(path)
    }

    /// One front buffer, 23 triangles after a fast fill, one swap, then two dumps.
    fn gouraud() -> (Vec<TraceOp>, BoardConfig) {
        let t = load_trace(&repo("traces/conformance/traces/gouraud_dither4.trace.gz")).unwrap();
        let config = t.board_config();
        (t.ops, config)
    }

    /// `buffer` of a fresh board of `profile` after `ops`.
    fn direct(
        ops: &[TraceOp],
        config: BoardConfig,
        r: Option<Reference>,
        kind: BufferKind,
    ) -> Vec<u16> {
        let mut board = match r {
            Some(r) => board_of(config, r),
            None => Board::new(config),
        };
        execute(ops, &mut board, |_| {});
        board.dump_buffer(kind)
    }

    fn write(addr: u32) -> TraceOp {
        TraceOp::Write { addr, value: 0 }
    }

    fn dump() -> TraceOp {
        TraceOp::Dump {
            buffer: DumpBuffer::Front,
            file: "x.raw".into(),
        }
    }

    #[test]
    fn frames_end_at_swaps_and_lone_dumps_commands_at_each_drawing_op() {
        // swap, dump, dump, triangle, ftriangle, fastfill, dump, swap, a plain write.
        let ops = vec![
            write(0x128),
            dump(),
            dump(),
            write(0x080),
            write(0x100),
            write(0x124),
            dump(),
            write(0x128),
            write(0x110),
        ];
        let (frames, commands) = ends(&ops);
        assert_eq!(frames, [3, 7, 8]);
        assert_eq!(commands, [1, 2, 3, 4, 5, 6, 7, 8]);
    }

    #[test]
    fn a_frame_step_shows_the_swapped_frame_exactly() {
        let (ops, config) = gouraud();
        let dumps = execute(&ops, &mut Board::new(config), |_| {});
        let mut p = Player::new(ops.clone(), config, View::Hardware, None);
        assert_eq!((p.position(), p.frame_number()), ((0, ops.len()), 0));
        p.act(Action::NextFrame);
        // Through the swap and both dumps after it: the end of the trace.
        assert_eq!(
            (p.position(), p.frame_number()),
            ((ops.len(), ops.len()), 1)
        );
        let (w, h, front) = p.buffer();
        assert_eq!((w, h), (640, 480));
        assert_eq!(front, dumps[0].data);
        let (frame, failing) = p.render();
        assert_eq!(failing, None);
        assert_eq!(
            frame.pixels,
            dumps[0]
                .data
                .iter()
                .map(|&v| sst1_window::xrgb(v))
                .collect::<Vec<_>>()
        );
        p.act(Action::Show(Shown::Depth));
        assert_eq!(p.shown(), Shown::Depth);
        let grey: Vec<u32> = dumps[1]
            .data
            .iter()
            .map(|&d| u32::from(d >> 8) * 0x0001_0101)
            .collect();
        assert_eq!(p.render().0.pixels, grey);
        // No frame past the last: the player stays.
        p.act(Action::NextFrame);
        assert_eq!(p.position(), (ops.len(), ops.len()));
        p.act(Action::PreviousFrame);
        assert_eq!((p.position().0, p.frame_number()), (0, 0));
    }

    #[test]
    fn command_steps_stop_after_each_drawing_op_and_go_back_one() {
        let (ops, config) = gouraud();
        let mut p = Player::new(ops.clone(), config, View::Hardware, None);
        p.act(Action::Show(Shown::Back));
        let mut stops = Vec::new();
        loop {
            let at = p.position().0;
            p.act(Action::NextCommand);
            if p.position().0 == at {
                break;
            }
            stops.push(p.position().0);
            // Exactly what a fresh board shows after the same ops.
            assert_eq!(
                p.buffer().2,
                direct(&ops[..p.position().0], config, None, BufferKind::Back)
            );
        }
        // A fast fill, 23 triangles, the swap and two dumps.
        assert_eq!(stops.len(), 27);
        assert_eq!(*stops.last().unwrap(), ops.len());
        p.act(Action::PreviousCommand);
        assert_eq!(p.position().0, stops[25]);
        p.act(Action::PreviousCommand);
        assert_eq!(p.position().0, stops[24]);
        assert_eq!(p.frame_number(), 0);
        assert_eq!(
            p.buffer().2,
            direct(&ops[..stops[24]], config, None, BufferKind::Back)
        );
        p.act(Action::Restart);
        assert_eq!(p.position().0, 0);
    }

    #[test]
    fn every_model_shows_its_own_board_and_the_vote_votes() {
        let (ops, config) = gouraud();
        let mut p = Player::new(ops.clone(), config, View::Hardware, None);
        // Stop after the 10th triangle, mid-frame, on the back buffer.
        for _ in 0..11 {
            p.act(Action::NextCommand);
        }
        p.act(Action::Show(Shown::Back));
        let at = p.position().0;
        let refs = Reference::ALL.map(|r| direct(&ops[..at], config, Some(r), BufferKind::Back));
        let mut seen = vec![p.view()];
        for _ in 0..View::ALL.len() {
            let want = match p.view() {
                View::Hardware => direct(&ops[..at], config, None, BufferKind::Back),
                View::Vote => sst1_board::vote(&refs[0], &refs[1], &refs[2]),
                View::Reference(r) => {
                    refs[Reference::ALL.iter().position(|&x| x == r).unwrap()].clone()
                }
            };
            assert_eq!(p.buffer().2, want, "{}", p.view().name());
            p.act(Action::NextModel);
            seen.push(p.view());
        }
        assert_eq!(seen, [View::ALL.to_vec(), vec![View::Hardware]].concat());
    }

    #[test]
    fn the_diff_marks_exactly_the_pixels_off_the_goldens() {
        let (ops, config) = gouraud();
        let dumps = execute(&ops, &mut Board::new(config), |_| {});
        // A folder with one golden: ours with two pixels changed.
        let dir = std::env::temp_dir().join(format!("voodoo-play-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut golden = dumps[0].data.clone();
        golden[5] ^= 0x0800;
        golden[640 * 100 + 7] ^= 0x0001;
        std::fs::write(
            dir.join("gouraud_dither4_front.raw"),
            golden
                .iter()
                .flat_map(|v| v.to_le_bytes())
                .collect::<Vec<u8>>(),
        )
        .unwrap();
        let mut p = Player::new(ops, config, View::Hardware, Some(dir.clone()));
        p.act(Action::NextFrame);
        let (frame, failing) = p.render();
        assert_eq!(failing, Some(2));
        for (i, (&px, &ours)) in frame.pixels.iter().zip(&dumps[0].data).enumerate() {
            let want = if i == 5 || i == 640 * 100 + 7 {
                CONSENSUS_FAIL
            } else {
                (sst1_window::xrgb(ours) >> 1) & 0x007f_7f7f
            };
            assert_eq!(px, want, "pixel {i}");
        }
        assert!(p
            .title("t", failing)
            .starts_with("voodoo play t: frame 1, op 611/611, hardware front, 2 pixels off gouraud_dither4_front.raw | "));
        // The depth dump has no golden here; G turns the marks off.
        p.act(Action::Show(Shown::Depth));
        assert_eq!(p.render().1, None);
        p.act(Action::Show(Shown::Front));
        p.act(Action::ToggleDiff);
        assert_eq!(p.render().1, None);
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn the_conformance_goldens_judge_the_hardware_model_clean() {
        let (ops, config) = gouraud();
        let mut p = Player::new(
            ops,
            config,
            View::Hardware,
            Some(repo("traces/conformance/golden")),
        );
        p.act(Action::NextFrame);
        assert_eq!(p.render().1, Some(0));
    }

    #[test]
    fn h_draws_the_keys_over_the_bottom_of_the_picture() {
        let (ops, config) = gouraud();
        let mut p = Player::new(ops, config, View::Hardware, None);
        p.act(Action::NextFrame);
        let plain = p.render().0;
        p.act(Action::ToggleHelp);
        let helped = p.render().0;
        let mut want = plain.clone();
        let columns = sst1_window::text::columns(640);
        let mut lines = sst1_window::text::wrap("frame 1, op 611/611, hardware front", columns);
        lines.extend(sst1_window::text::wrap(KEYS, columns));
        sst1_window::text::draw_lines(&mut want, &lines);
        assert_eq!(helped, want);
        // Three lines of keys and the status: the picture above them is untouched.
        assert_eq!(lines.len(), 4);
        let strip = 640 * (480 - (4 * 14 + 8));
        assert_eq!(helped.pixels[..strip], plain.pixels[..strip]);
        assert_ne!(helped.pixels[strip..], plain.pixels[strip..]);
        p.act(Action::ToggleHelp);
        assert_eq!(p.render().0, plain);
    }

    #[test]
    fn keys_map_to_actions() {
        use sst1_window::Key;
        assert_eq!(Action::of(&Key::Right), Some(Action::NextFrame));
        assert_eq!(Action::of(&Key::Char('n')), Some(Action::NextCommand));
        assert_eq!(
            Action::of(&Key::Char('d')),
            Some(Action::Show(Shown::Depth))
        );
        assert_eq!(Action::of(&Key::Char('q')), Some(Action::Quit));
        assert_eq!(Action::of(&Key::Char('z')), None);
    }
}
