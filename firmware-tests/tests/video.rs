//! Video timing (spec 10, 5.37-5.39, 5.43, 5.48): the frame's period follows `hSync`,
//! `vSync` and the pixel clock the DAC's PLL is programmed with; `status` bit 6 reads the
//! vertical retrace and `vRetrace` the scan line since the last one.

use firmware_tests::{Emulator, Port, PCI_INIT_ENABLE};
use sst1_regs::addr;

/// 640x480 at 60 Hz as 3dfx's init library sets it (glide3 `video`): `hSync` 96/704
/// (802 VCLKs a line), `vSync` 2/523 (525 lines).
const H_SYNC: u32 = 0x02c0_0060;
const V_SYNC: u32 = 0x020b_0002;
/// `fbiInit1` as the conformance traces leave it, with the VCLK source (bits 21:20) 1:
/// `vid_clk_2x` / 2, the 24-bit output's.
const FBI_INIT1_24BPP: u32 = 0x0020_00a2 & !(3 << 20) | 1 << 20;
/// The DAC writes of glide3 `set_vid_clk(50.35)` for that mode's 24-bit output (ICS5342
/// through `dacData`: PLL address 0, M = 0x7d, P << 5 | N = 0x47, then the control
/// register 0xe selecting clock 0 from register 0). 14.31818 MHz * 127 / (9 * 4) =
/// 50.511 MHz, halved: 25.256 MHz, a frame of 16.6715 ms (833,574.75 clocks).
const DAC_50_35_MHZ: [u32; 5] = [0x400, 0x57d, 0x547, 0x40e, 0x5f8];

/// Programs the mode: three register writes, and the DAC's five when `pll`.
fn set_mode(p: &mut impl Port, pll: bool) {
    p.pci_write(PCI_INIT_ENABLE, 3);
    p.write(addr::H_SYNC, H_SYNC);
    p.write(addr::V_SYNC, V_SYNC);
    p.write(addr::FBI_INIT1, FBI_INIT1_24BPP);
    if pll {
        for v in DAC_50_35_MHZ {
            p.write(addr::DAC_DATA, v);
        }
    }
}

/// `vRetrace` at a given time: the frame starts at power-on with the lines before the
/// sync, each 1/525 of the frame. After the eight writes (12 clocks) and 381,840 clocks
/// of waiting, the read (4.5 clocks) lands at 381,856.5 clocks: line 240 of a 833,574.75
/// clock frame. Near the frame's end the two clocks differ: at 830,249.5 clocks it is
/// line 522 of the PLL's frame, and the retrace (`vRetrace` 0, `status` bit 6 clear) of
/// the 60 Hz frame (833,333.3 clocks), which starts 0.24 us earlier, at line 523.
///
/// Source: spec 5.37 (`vRetrace`: the `vSync_off` counter), spec 10 (the line and frame
/// lengths). UNVERIFIED: the counter's phase after power-on and its value during sync.
#[test]
fn v_retrace_reads_the_scan_line_at_a_given_time() {
    let mut p = Emulator::new();
    set_mode(&mut p, true);
    p.wait(381_840);
    assert_eq!(p.read(addr::V_RETRACE), 240);
    assert_eq!(p.board().timing().frame().period, 13_337_196);

    let mut p = Emulator::new();
    set_mode(&mut p, true);
    p.wait(830_233);
    assert_eq!(p.read(addr::V_RETRACE), 522);
    assert_eq!(p.read(addr::STATUS) >> 6 & 1, 1, "no retrace yet");
    p.wait(200);
    assert_eq!(p.read(addr::V_RETRACE), 0, "the retrace has begun");
    assert_eq!(p.read(addr::STATUS) >> 6 & 1, 0);

    // Without the PLL: 60 Hz, 525 lines.
    let mut p = Emulator::new();
    set_mode(&mut p, false);
    p.wait(830_233);
    assert_eq!(p.read(addr::V_RETRACE), 0);
    assert_eq!(p.read(addr::STATUS) >> 6 & 1, 0);
    assert_eq!(p.board().timing().frame().period, 13_333_333);
}

/// Reads between two starts of the vertical retrace: the frame's period at 4.5 clocks a
/// read (a status read takes 3 PCI clocks in the model). A real board should count
/// 16.67 ms of reads either way; the model's count follows the PLL.
fn reads_per_frame(p: &mut impl Port) -> u32 {
    while in_retrace(p) {}
    while !in_retrace(p) {}
    // From the read that saw the retrace begin to the one that sees the next begin.
    let mut reads = 1;
    while in_retrace(p) {
        reads += 1;
    }
    reads += 1;
    while !in_retrace(p) {
        reads += 1;
    }
    reads
}

/// `status` bit 6 clear: the vertical retrace is active (spec 5.1).
fn in_retrace(p: &mut impl Port) -> bool {
    p.read(addr::STATUS) >> 6 & 1 == 0
}

/// The frame's period follows the pixel clock: 833,574.75 clocks with the PLL at
/// 50.511 MHz halved (185,238.8 reads of 4.5 clocks), 416,787.4 with the same clock not
/// halved (16-bit output's source, `fbiInit1` bits 21:20 = 3), 833,333.3 (60 Hz) with
/// no PLL programmed; the same on every run.
///
/// Source: spec 10 and 5.43 bits 21:20; the DAC's PLL equation (ICS5342, as 3dfx's init
/// library programs it).
#[test]
fn the_frame_period_follows_the_pixel_clock() {
    let mut p = Emulator::booted();
    set_mode(&mut p, true);
    let pll = reads_per_frame(&mut p);
    assert!((185_238..=185_239).contains(&pll), "{pll}");
    p.write(addr::FBI_INIT1, FBI_INIT1_24BPP | 3 << 20);
    let pll16 = reads_per_frame(&mut p);
    assert!((92_619..=92_620).contains(&pll16), "{pll16}");
    let mut q = Emulator::booted();
    set_mode(&mut q, false);
    let sixty = reads_per_frame(&mut q);
    assert!((185_185..=185_186).contains(&sixty), "{sixty}");
    let mut again = Emulator::booted();
    set_mode(&mut again, true);
    assert_eq!(reads_per_frame(&mut again), pll);
}

/// Between two retraces `vRetrace` counts the 523 lines of `vSync_off` up from 0, one
/// line per 802 VCLKs (about 352.8 reads of 4.5 clocks); during the retrace it reads 0.
///
/// Source: spec 5.37 and 10. A real board should show the same climb from 0 to 522.
#[test]
fn v_retrace_counts_up_between_syncs() {
    let mut p = Emulator::booted();
    set_mode(&mut p, true);
    while !in_retrace(&mut p) {}
    assert_eq!(p.read(addr::V_RETRACE), 0);
    while in_retrace(&mut p) {}
    let mut last = 0;
    let mut reads_on_line = 0;
    let mut longest = 0;
    loop {
        let line = p.read(addr::V_RETRACE);
        if line == 0 && last > 0 {
            break;
        }
        assert!(line == last || line == last + 1, "{last} -> {line}");
        if line == last {
            reads_on_line += 1;
        } else {
            longest = longest.max(reads_on_line);
            reads_on_line = 1;
        }
        last = line;
    }
    assert_eq!(last, 522);
    assert!((352..=354).contains(&longest), "{longest}");
    assert!(in_retrace(&mut p));
}

/// Each video register alone retimes the frame: after the mode is set, a longer line
/// (`hSync`'s back porch 720 instead of 704 VCLKs) or more lines (`vSync` 2/539) alone
/// make the frame longer, each write by itself.
///
/// Source: spec 10 (the line and frame lengths).
#[test]
fn each_video_register_alone_retimes_the_frame() {
    let mut p = Emulator::new();
    set_mode(&mut p, true);
    let before = p.board().timing().frame().period;
    p.write(addr::H_SYNC, 0x02d0_0060);
    let longer_lines = p.board().timing().frame().period;
    assert!(longer_lines > before, "{longer_lines} after {before}");
    p.write(addr::V_SYNC, 0x021b_0002);
    let more_lines = p.board().timing().frame().period;
    assert!(
        more_lines > longer_lines,
        "{more_lines} after {longer_lines}"
    );
}
