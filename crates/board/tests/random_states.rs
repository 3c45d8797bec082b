//! The fast path (the span kernels) against the reference path
//! (`Board::set_generic_path(true)`) on drawing states no recorded trace uses: scenes of
//! `sst1_trace::scenes::random_states` (every stored bit of `fbzColorPath`, `fogMode`,
//! `alphaMode` and `fbzMode` at random, random `textureMode`/`tLOD`/`tDetail`, texture
//! contents, NCC tables, palette, fog table, chroma key, `zaColor`, stipple and clip per
//! state, 1 to 3 TMUs), replayed both ways for the hardware model and for each reference
//! model's profile. Every dump, the final front, back and aux buffers and the statistics
//! counters must be identical.
//!
//! The test also counts, on the hardware model's fast-path replay, which selection of
//! each stage the scenes reached (a triangle *reaches* the colour path, the TMUs and the
//! tests after depth when some of its pixels passed the depth test, and the fog, blend
//! and dither stages when some were written; `fbiChromaFail`, `fbiZfuncFail`,
//! `fbiAfuncFail` and `fbiPixelsOut` tell), and requires every selection to be reached at
//! least once, so that a pass proves every kernel was compared. Run with `--nocapture`
//! for the table.
//!
//! On a difference it replays the failing scene again, both paths in lockstep, and names
//! the first triangle after which the buffers or counters differ, with the mode
//! registers in force (decoded): the state to report.

use std::collections::BTreeMap;

use sst1_board::{AccuracyProfile, Board, BufferKind, Reference, Stats, VectorIsa};
use sst1_regs::{addr, map};
use sst1_trace::scenes::{random_states, RandomStates};
use sst1_trace::{execute, read_trace, Trace, TraceOp};

/// The scenes: (seed, TMUs). Three of each TMU count, a random frame-buffer layout in
/// seeds 3, 6 and 9 (one of each TMU count); 300 states of two triangles each.
const SCENES: &[(u64, u32)] = &[
    (1, 1),
    (2, 2),
    (3, 3),
    (4, 3),
    (5, 2),
    (6, 1),
    (7, 1),
    (8, 3),
    (9, 2),
];
const STATES: u32 = 300;

fn scene(seed: u64, tmus: u32) -> Trace {
    let text = random_states(RandomStates {
        seed,
        tmus,
        states: STATES,
        triangles_per_state: 2,
        dump_every: 50,
        // A random frame-buffer layout in every third scene.
        layout: seed.is_multiple_of(3),
        large: false,
    });
    read_trace(&format!("random_states seed {seed}"), text.as_bytes())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The registers last written to the FBI and to each TMU (chip field decoded; the
/// scenes never remap), to know the state a triangle ran in.
#[derive(Clone)]
struct Shadow {
    fbi: [u32; 256],
    tmu: [[u32; 256]; 3],
}

impl Shadow {
    fn new() -> Self {
        Self {
            fbi: [0; 256],
            tmu: [[0; 256]; 3],
        }
    }

    fn write(&mut self, a: u32, value: u32) {
        if a >= 0x40_0000 {
            return;
        }
        let index = addr::index(a);
        let chips = match (a >> 10) & 0xf {
            0 => 0xf,
            c => c,
        };
        if chips & 1 != 0 {
            self.fbi[index] = value;
        }
        for (t, regs) in self.tmu.iter_mut().enumerate() {
            if chips & (2 << t) != 0 {
                regs[index] = value;
            }
        }
    }

    fn fbi(&self, offset: u32) -> u32 {
        self.fbi[addr::index(offset)]
    }

    fn tmu(&self, t: usize, offset: u32) -> u32 {
        self.tmu[t][addr::index(offset)]
    }

    /// The mode registers in force, decoded, one per line.
    fn describe(&self, tmus: usize) -> String {
        let mut out = String::new();
        for reg in [
            addr::FBZ_COLOR_PATH,
            addr::FOG_MODE,
            addr::ALPHA_MODE,
            addr::FBZ_MODE,
            addr::CLIP_LEFT_RIGHT,
            addr::CLIP_LOW_Y_HIGH_Y,
            addr::ZA_COLOR,
            addr::CHROMA_KEY,
            addr::STIPPLE,
            addr::COLOR0,
            addr::COLOR1,
            addr::FOG_COLOR,
        ] {
            let v = self.fbi(reg) & map::mask_of(reg);
            out += &format!(
                "  {:<14} {v:#010x} {}\n",
                map::name_of(reg),
                map::decode(reg, v)
            );
        }
        for t in 0..tmus {
            for reg in [
                addr::TEXTURE_MODE,
                addr::T_LOD,
                addr::T_DETAIL,
                addr::TEX_BASE_ADDR,
            ] {
                let v = self.tmu(t, reg);
                out += &format!(
                    "  tmu{t} {:<12} {v:#010x} {}\n",
                    map::name_of(reg),
                    map::decode(reg, v)
                );
            }
        }
        out
    }
}

/// Whether a write starts a triangle (`triangleCMD` or `ftriangleCMD`).
fn is_triangle(a: u32) -> bool {
    a < 0x40_0000 && matches!(a & 0x3fc, addr::TRIANGLE_CMD | addr::F_TRIANGLE_CMD)
}

/// How many triangles reached each selection of each stage, by name.
#[derive(Default)]
struct Coverage {
    reached: BTreeMap<String, u64>,
    /// Every selection that must be reached.
    expected: Vec<String>,
}

impl Coverage {
    fn hit(&mut self, name: String) {
        *self.reached.entry(name).or_default() += 1;
    }

    /// A field's value as `prefix=value`.
    fn field(&mut self, prefix: &str, value: u32) {
        self.hit(format!("{prefix}={value}"));
    }

    fn expect(&mut self, prefix: &str, values: u32) {
        for v in 0..values {
            self.expected.push(format!("{prefix}={v}"));
        }
    }

    /// The list of selections every run must reach (for a board of `tmus` TMUs).
    fn new(max_tmus: usize) -> Self {
        let mut c = Self::default();
        for (name, n) in [
            ("cc_rgbselect", 4),
            ("cc_aselect", 4),
            ("cc_localselect", 2),
            ("cca_localselect", 4),
            ("cc_localselect_override", 2),
            ("cc_zero_other", 2),
            ("cc_sub_clocal", 2),
            ("cc_mselect", 8),
            ("cc_reverse_blend", 2),
            ("cc_add", 4),
            ("cc_invert_output", 2),
            ("cca_zero_other", 2),
            ("cca_sub_clocal", 2),
            ("cca_mselect", 8),
            ("cca_reverse_blend", 2),
            ("cca_add", 4),
            ("cca_invert_output", 2),
            ("param_adjust", 2),
            ("texture_enable", 2),
            ("chromakey", 2),
            ("alpha_mask", 2),
            ("alpha_function", 8),
            ("alpha_test_enable", 2),
            ("depth_function", 8),
            ("depth_source", 3),
            ("depth_bias", 2),
            ("depth_source_compare", 2),
            ("stipple", 3),
            ("y_origin", 2),
            ("clipping", 2),
            ("src_rgb_blend", 16),
            ("dst_rgb_blend", 16),
            ("src_alpha_blend", 16),
            ("dst_alpha_blend", 16),
            ("alpha_blend_enable", 2),
            ("fog", 2),
            ("fog_za", 4),
            ("fog_add", 2),
            ("fog_mult", 2),
            ("fog_constant", 2),
            ("dither", 3),
            ("dither_subtract", 2),
            ("draw_buffer", 4),
            ("rgb_buffer_mask", 2),
            ("aux_buffer_mask", 2),
            ("alpha_planes", 2),
            ("kill_chroma", 1),
            ("kill_zfunc", 1),
            ("kill_afunc", 1),
            // Textured triangles whose pixels read the texel or not (the span kernels
            // skip the TMUs where none does).
            ("texel_read", 2),
            ("colour_written", 2),
        ] {
            c.expect(name, n);
        }
        // TMUs whose combine reads the upstream TMU's output or not (the span kernels
        // skip the upstream TMUs where it does not).
        for t in 0..max_tmus.saturating_sub(1) {
            c.expect(&format!("tmu{t}.reads_other"), 2);
        }
        for t in 0..max_tmus {
            for (name, n) in [
                ("format", 16),
                ("filter_min_mag", 4),
                ("tpersp_st", 2),
                ("tclamps", 2),
                ("tclampt", 2),
                ("tclampw", 2),
                ("tloddither", 2),
                ("tnccselect", 2),
                ("tc_zero_other", 2),
                ("tc_sub_clocal", 2),
                ("tc_mselect", 8),
                ("tc_reverse_blend", 2),
                ("tc_add", 4),
                ("tc_invert_output", 2),
                ("tca_zero_other", 2),
                ("tca_sub_clocal", 2),
                ("tca_mselect", 8),
                ("tca_reverse_blend", 2),
                ("tca_add", 4),
                ("tca_invert_output", 2),
                ("trilinear", 2),
                ("lod_aspect", 4),
                ("lod_s_is_wider", 2),
                ("lod_tsplit_odd", 4),
                ("lod_zerofrac", 2),
                ("tmultibaseaddr", 2),
            ] {
                c.expect(&format!("tmu{t}.{name}"), n);
            }
        }
        c
    }

    /// Counts the selections one triangle reached, from the state it ran in and what its
    /// pixels did to the counters.
    fn triangle(&mut self, s: &Shadow, tmus: usize, d: &Stats) {
        let bit = |v: u32, b: u32| (v >> b) & 1;
        let bits = |v: u32, hi: u32, lo: u32| (v >> lo) & ((1 << (hi - lo + 1)) - 1);
        let cp = s.fbi(addr::FBZ_COLOR_PATH);
        let fog = s.fbi(addr::FOG_MODE);
        let am = s.fbi(addr::ALPHA_MODE);
        let fbz = s.fbi(addr::FBZ_MODE);
        // Pixels that reached the depth test, got past it, and were written.
        let at_depth = d.zfunc_fail + d.chroma_fail + d.afunc_fail + d.pixels_out;
        let past_depth = d.chroma_fail + d.afunc_fail + d.pixels_out;
        let written = d.pixels_out;
        if d.chroma_fail > 0 {
            self.field("kill_chroma", 0);
        }
        if d.zfunc_fail > 0 {
            self.field("kill_zfunc", 0);
        }
        if d.afunc_fail > 0 {
            self.field("kill_afunc", 0);
        }
        // Every triangle: the reserved buffers 2 and 3 draw nothing at all.
        self.field("draw_buffer", bits(fbz, 15, 14));
        if at_depth > 0 {
            self.field("clipping", bit(fbz, 0));
            self.field(
                "stipple",
                if bit(fbz, 2) == 0 {
                    0
                } else {
                    1 + bit(fbz, 12)
                },
            );
            self.field("y_origin", bit(fbz, 17));
            self.field("param_adjust", bit(cp, 26));
            if bit(fbz, 4) == 1 {
                self.field("depth_function", bits(fbz, 7, 5));
            }
            // Z, W, or zaColor's depth (with depth_source_compare) as the value compared.
            self.field(
                "depth_source",
                if bit(fbz, 20) == 1 { 2 } else { bit(fbz, 3) },
            );
            self.field("depth_bias", bit(fbz, 16));
            self.field("depth_source_compare", bit(fbz, 20));
        }
        if past_depth > 0 {
            self.field("cc_rgbselect", bits(cp, 1, 0));
            self.field("cc_aselect", bits(cp, 3, 2));
            self.field("cc_localselect", bit(cp, 4));
            self.field("cca_localselect", bits(cp, 6, 5));
            self.field("cc_localselect_override", bit(cp, 7));
            self.field("cc_zero_other", bit(cp, 8));
            self.field("cc_sub_clocal", bit(cp, 9));
            self.field("cc_mselect", bits(cp, 12, 10));
            self.field("cc_reverse_blend", bit(cp, 13));
            self.field("cc_add", bits(cp, 15, 14));
            self.field("cc_invert_output", bit(cp, 16));
            self.field("cca_zero_other", bit(cp, 17));
            self.field("cca_sub_clocal", bit(cp, 18));
            self.field("cca_mselect", bits(cp, 21, 19));
            self.field("cca_reverse_blend", bit(cp, 22));
            self.field("cca_add", bits(cp, 24, 23));
            self.field("cca_invert_output", bit(cp, 25));
            self.field("texture_enable", bit(cp, 27));
            // RGB or alpha planes written (the span kernels skip fog and the blend
            // where neither is).
            self.field(
                "colour_written",
                u32::from(bit(fbz, 9) == 1 || (bit(fbz, 10) == 1 && bit(fbz, 18) == 1)),
            );
            self.field("chromakey", bit(fbz, 1));
            self.field("alpha_mask", bit(fbz, 13));
            self.field("alpha_test_enable", bit(am, 0));
            if bit(am, 0) == 1 {
                self.field("alpha_function", bits(am, 3, 1));
            }
            if bit(cp, 27) == 1 {
                let read = pixelfx::color_path::texel_read(
                    sst1_regs::FbzColorPath(cp),
                    sst1_regs::FbzMode(fbz),
                    sst1_regs::AlphaMode(am),
                    pixelfx::PixelProfile::default().alpha_test_input
                        == pixelfx::profile::AlphaTestInput::Combined,
                    bit(fbz, 9) == 1,
                    bit(fbz, 10) == 1 && bit(fbz, 18) == 1,
                );
                self.field("texel_read", u32::from(read));
                for t in 0..tmus.saturating_sub(1) {
                    let tm = s.tmu(t, addr::TEXTURE_MODE);
                    let reads = |zero_other: u32, mselect: u32| zero_other == 0 || mselect == 2;
                    let reads_other = reads(bit(tm, 12), bits(tm, 16, 14))
                        || reads(bit(tm, 21), bits(tm, 25, 23));
                    self.field(&format!("tmu{t}.reads_other"), u32::from(reads_other));
                }
                for t in 0..tmus {
                    let tm = s.tmu(t, addr::TEXTURE_MODE);
                    let lod = s.tmu(t, addr::T_LOD);
                    let p = format!("tmu{t}.");
                    self.field(&(p.clone() + "format"), bits(tm, 11, 8));
                    self.field(&(p.clone() + "filter_min_mag"), bits(tm, 2, 1));
                    self.field(&(p.clone() + "tpersp_st"), bit(tm, 0));
                    self.field(&(p.clone() + "tclampw"), bit(tm, 3));
                    self.field(&(p.clone() + "tloddither"), bit(tm, 4));
                    self.field(&(p.clone() + "tnccselect"), bit(tm, 5));
                    self.field(&(p.clone() + "tclamps"), bit(tm, 6));
                    self.field(&(p.clone() + "tclampt"), bit(tm, 7));
                    self.field(&(p.clone() + "tc_zero_other"), bit(tm, 12));
                    self.field(&(p.clone() + "tc_sub_clocal"), bit(tm, 13));
                    self.field(&(p.clone() + "tc_mselect"), bits(tm, 16, 14));
                    self.field(&(p.clone() + "tc_reverse_blend"), bit(tm, 17));
                    self.field(&(p.clone() + "tc_add"), bits(tm, 19, 18));
                    self.field(&(p.clone() + "tc_invert_output"), bit(tm, 20));
                    self.field(&(p.clone() + "tca_zero_other"), bit(tm, 21));
                    self.field(&(p.clone() + "tca_sub_clocal"), bit(tm, 22));
                    self.field(&(p.clone() + "tca_mselect"), bits(tm, 25, 23));
                    self.field(&(p.clone() + "tca_reverse_blend"), bit(tm, 26));
                    self.field(&(p.clone() + "tca_add"), bits(tm, 28, 27));
                    self.field(&(p.clone() + "tca_invert_output"), bit(tm, 29));
                    self.field(&(p.clone() + "trilinear"), bit(tm, 30));
                    self.field(&(p.clone() + "lod_tsplit_odd"), bits(lod, 19, 18));
                    self.field(&(p.clone() + "lod_s_is_wider"), bit(lod, 20));
                    self.field(&(p.clone() + "lod_aspect"), bits(lod, 22, 21));
                    self.field(&(p.clone() + "lod_zerofrac"), bit(lod, 23));
                    self.field(&(p + "tmultibaseaddr"), bit(lod, 24));
                }
            }
        }
        if written > 0 {
            self.field("alpha_blend_enable", bit(am, 4));
            if bit(am, 4) == 1 {
                self.field("src_rgb_blend", bits(am, 11, 8));
                self.field("dst_rgb_blend", bits(am, 15, 12));
                self.field("src_alpha_blend", bits(am, 19, 16));
                self.field("dst_alpha_blend", bits(am, 23, 20));
            }
            self.field("fog", bit(fog, 0));
            if bit(fog, 0) == 1 {
                self.field("fog_add", bit(fog, 1));
                self.field("fog_mult", bit(fog, 2));
                self.field("fog_za", bits(fog, 4, 3));
                self.field("fog_constant", bit(fog, 5));
            }
            self.field(
                "dither",
                if bit(fbz, 8) == 0 {
                    0
                } else {
                    1 + bit(fbz, 11)
                },
            );
            self.field("dither_subtract", bit(fbz, 19));
            self.field("rgb_buffer_mask", bit(fbz, 9));
            self.field("aux_buffer_mask", bit(fbz, 10));
            self.field("alpha_planes", bit(fbz, 18));
        }
    }
}

/// What one replay produced: every dump and the final buffers, and the counters.
#[derive(PartialEq, Eq)]
struct Outcome {
    buffers: Vec<(String, Vec<u16>)>,
    stats: Stats,
}

/// How a replay draws: the reference path, or the fast path with this copy of the span
/// kernels (only the hardware model has more than the baseline copy).
#[derive(Clone, Copy, Debug)]
enum Draw {
    Reference,
    Fast(VectorIsa),
}

fn board(trace: &Trace, profile: AccuracyProfile, draw: Draw) -> Board {
    let mut board = Board::new(trace.board_config());
    board.set_profile(profile);
    match draw {
        Draw::Reference => board.set_generic_path(true),
        Draw::Fast(isa) => {
            board.set_vector_isa(isa);
        }
    }
    board
}

fn final_buffers(board: &Board, buffers: &mut Vec<(String, Vec<u16>)>) {
    for (name, kind) in [
        ("final front", BufferKind::Front),
        ("final back", BufferKind::Back),
        ("final aux", BufferKind::Aux),
    ] {
        buffers.push((name.to_owned(), board.dump_buffer(kind)));
    }
}

/// Replays a whole scene; with `coverage`, counts the selections each triangle reached.
fn replay(
    trace: &Trace,
    profile: AccuracyProfile,
    draw: Draw,
    mut coverage: Option<&mut Coverage>,
) -> Outcome {
    let mut board = board(trace, profile, draw);
    let tmus = trace.board_config().tmus as usize;
    let mut shadow = Shadow::new();
    let mut buffers = Vec::new();
    for op in &trace.ops {
        let before = board.stats();
        buffers.extend(
            execute(std::slice::from_ref(op), &mut board, |_| {})
                .into_iter()
                .map(|d| (d.file, d.data)),
        );
        if let (Some(c), TraceOp::Write { addr, value }) = (coverage.as_deref_mut(), op) {
            shadow.write(*addr, *value);
            if is_triangle(*addr) {
                let after = board.stats();
                let delta = Stats {
                    pixels_in: after.pixels_in - before.pixels_in,
                    chroma_fail: after.chroma_fail - before.chroma_fail,
                    zfunc_fail: after.zfunc_fail - before.zfunc_fail,
                    afunc_fail: after.afunc_fail - before.afunc_fail,
                    pixels_out: after.pixels_out - before.pixels_out,
                    ..Stats::default()
                };
                c.triangle(&shadow, tmus, &delta);
            }
        }
    }
    final_buffers(&board, &mut buffers);
    Outcome {
        buffers,
        stats: board.stats(),
    }
}

/// Both paths in lockstep: the first triangle after which the buffers or counters differ,
/// with the state it ran in.
fn first_difference(trace: &Trace, profile: AccuracyProfile, isa: VectorIsa) -> String {
    let mut fast = board(trace, profile, Draw::Fast(isa));
    let mut slow = board(trace, profile, Draw::Reference);
    let tmus = trace.board_config().tmus as usize;
    let mut shadow = Shadow::new();
    let mut triangle = 0u64;
    let kinds = [BufferKind::Front, BufferKind::Back, BufferKind::Aux];
    for (i, op) in trace.ops.iter().enumerate() {
        execute(std::slice::from_ref(op), &mut fast, |_| {});
        execute(std::slice::from_ref(op), &mut slow, |_| {});
        let TraceOp::Write { addr, value } = op else {
            continue;
        };
        shadow.write(*addr, *value);
        if !is_triangle(*addr) {
            continue;
        }
        triangle += 1;
        let stats_differ = fast.stats() != slow.stats();
        let buffer = kinds.iter().find_map(|&k| {
            let (f, s) = (fast.dump_buffer(k), slow.dump_buffer(k));
            let n = f.iter().zip(&s).filter(|(a, b)| a != b).count();
            let first = f.iter().zip(&s).position(|(a, b)| a != b)?;
            let w = fast.display_size().0 as usize;
            Some(format!(
                "{k:?}: {n} values differ; first at (x {}, y {}): reference {:04x} fast {:04x}",
                first % w,
                first / w,
                s[first],
                f[first]
            ))
        });
        if stats_differ || buffer.is_some() {
            return format!(
                "first difference after triangle {triangle} (op {i}): {}\n  counters reference {:?}\n  counters fast      {:?}\nstate:\n{}",
                buffer.unwrap_or_else(|| "buffers equal".to_owned()),
                slow.stats(),
                fast.stats(),
                shadow.describe(tmus)
            );
        }
    }
    "no triangle differs (a dump or fill does)".to_owned()
}

/// The fast path with each of `isas` against the reference path; `coverage` counts the
/// first fast replay's selections.
fn compare(
    name: &str,
    trace: &Trace,
    profile: AccuracyProfile,
    isas: &[VectorIsa],
    mut coverage: Option<&mut Coverage>,
) -> Vec<String> {
    let reference = replay(trace, profile, Draw::Reference, None);
    isas.iter()
        .filter_map(|&isa| {
            let fast = replay(trace, profile, Draw::Fast(isa), coverage.take());
            difference(name, trace, profile, isa, &fast, &reference)
        })
        .collect()
}

/// What differs between a fast replay with `isa` and the reference replay, if anything.
fn difference(
    name: &str,
    trace: &Trace,
    profile: AccuracyProfile,
    isa: VectorIsa,
    fast: &Outcome,
    reference: &Outcome,
) -> Option<String> {
    if fast == reference {
        return None;
    }
    let mut report = format!("{name}: the fast path ({isa}) and the reference path differ\n");
    if fast.stats != reference.stats {
        report += &format!(
            "  counters reference {:?}\n  counters fast      {:?}\n",
            reference.stats, fast.stats
        );
    }
    for ((n, f), (_, r)) in fast.buffers.iter().zip(&reference.buffers) {
        let count = f.iter().zip(r).filter(|(a, b)| a != b).count();
        if count > 0 {
            report += &format!("  {n}: {count} values differ\n");
        }
    }
    report += &first_difference(trace, profile, isa);
    Some(report)
}

#[test]
fn random_states_identical_with_every_selection_reached() {
    let mut coverage = Coverage::new(3);
    let mut problems = Vec::new();
    let profiles: Vec<(&str, AccuracyProfile)> = [("hardware", AccuracyProfile::default())]
        .into_iter()
        .chain(Reference::ALL.iter().map(|r| (r.golden_dir(), r.profile())))
        .collect();
    for &(seed, tmus) in SCENES {
        let trace = scene(seed, tmus);
        for &(model, profile) in &profiles {
            let name = format!("seed {seed}, {tmus} TMUs, {model} model");
            let hardware = model == "hardware";
            let cov = hardware.then_some(&mut coverage);
            // The hardware model's every copy of the kernels; the others have one.
            let isas: Vec<VectorIsa> = if hardware {
                VectorIsa::available().collect()
            } else {
                vec![VectorIsa::Baseline]
            };
            problems.extend(compare(&name, &trace, profile, &isas, cov));
        }
    }
    println!("selections reached (triangles):");
    for (name, n) in &coverage.reached {
        println!("  {name:<28} {n}");
    }
    let missing: Vec<&String> = coverage
        .expected
        .iter()
        .filter(|e| !coverage.reached.contains_key(*e))
        .collect();
    assert!(
        problems.is_empty(),
        "{} difference(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
    assert!(missing.is_empty(), "selections never reached: {missing:?}");
}

/// More scenes than CI runs, for a longer search: seeds 100 to 100 + `VOODOO_SOAK_SCENES`
/// (default 60), TMUs and layout varying with the seed.
/// `cargo test --release -p sst1-board --test random_states -- --ignored`.
#[test]
#[ignore = "about a minute and a half in release: a longer search for differences"]
fn random_states_soak() {
    let scenes: u64 = std::env::var("VOODOO_SOAK_SCENES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(60);
    let mut problems = Vec::new();
    for seed in 100..100 + scenes {
        let tmus = 1 + ((seed / 3) % 3) as u32;
        let trace = scene(seed, tmus);
        let isas: Vec<VectorIsa> = VectorIsa::available().collect();
        problems.extend(compare(
            &format!("seed {seed}, {tmus} TMUs, hardware model"),
            &trace,
            AccuracyProfile::default(),
            &isas,
            None,
        ));
        for r in Reference::ALL {
            let name = format!("seed {seed}, {tmus} TMUs, {} model", r.golden_dir());
            problems.extend(compare(
                &name,
                &trace,
                r.profile(),
                &[VectorIsa::Baseline],
                None,
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "{} difference(s):\n{}",
        problems.len(),
        problems.join("\n")
    );
}

/// Large triangles in random states (`scenes::heavy_states`, 4 states of 96 triangles):
/// the wide chunks and the render threads' bands in states no trace uses. The fast path
/// with every copy of the kernels on 1, 2 and 4 render threads gives the reference
/// path's buffers and counters, and some of the triangles ran on the threads (in this
/// scene, 269,000 of their pixels in rows that start left of column 0).
#[test]
fn heavy_states_identical_on_every_thread_count() {
    let text = sst1_trace::scenes::heavy_states(5, 4);
    let trace = read_trace("heavy states", text.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    let profile = AccuracyProfile::default();
    let reference = replay(&trace, profile, Draw::Reference, None);
    let mut problems = Vec::new();
    let mut threaded = 0;
    for isa in VectorIsa::available() {
        for threads in [1, 2, 4] {
            let mut board = board(&trace, profile, Draw::Fast(isa));
            board.set_threads(threads);
            let mut buffers: Vec<(String, Vec<u16>)> = execute(&trace.ops, &mut board, |_| {})
                .into_iter()
                .map(|d| (d.file, d.data))
                .collect();
            final_buffers(&board, &mut buffers);
            let fast = Outcome {
                buffers,
                stats: board.stats(),
            };
            if threads > 1 {
                threaded += board.path_counts().in_bands;
            }
            if let Some(d) = difference(
                &format!("{threads} threads"),
                &trace,
                profile,
                isa,
                &fast,
                &reference,
            ) {
                problems.push(d);
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(
        threaded > 100_000,
        "{threaded} pixels shaded on the render threads"
    );
}

/// The generator is a function of its parameters: the same scene twice, and a different
/// one for another seed.
#[test]
fn scenes_are_deterministic() {
    let p = RandomStates {
        seed: 9,
        tmus: 2,
        states: 5,
        ..RandomStates::default()
    };
    assert_eq!(random_states(p), random_states(p));
    assert_ne!(
        random_states(p),
        random_states(RandomStates { seed: 10, ..p })
    );
    let small = sst1_trace::scenes::small_triangles(3, 50, true);
    assert_eq!(small, sst1_trace::scenes::small_triangles(3, 50, true));
    let trace = read_trace("small", small.as_bytes()).unwrap_or_else(|e| panic!("{e}"));
    let mut b = Board::new(trace.board_config());
    execute(&trace.ops, &mut b, |_| {});
    assert_eq!(b.stats().triangles, 50);
    // About 10 pixels each.
    let per = b.stats().pixels_in as f64 / 50.0;
    assert!((6.0..14.0).contains(&per), "{per} pixels per triangle");
}
