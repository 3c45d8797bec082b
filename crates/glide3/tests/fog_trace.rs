//! `guFogGenerateExp` + `grFogTable` must write the `fogTable` registers (0x160..0x1dc)
//! exactly as 3dfx's SST-1 Glide 3 did in the glide-sdk traces: test08 (density
//! 0.01), test22 (0.2) and test24 (0.9) (glide3x/sst1/glide3/tests/testNN.c).

mod common;
use common::{trace, Op, Rec};
use glide::get::{fog_generate_exp, FOG_TABLE_SIZE};
use glide::{BoardInfo, Glide};

const FOG_TABLE: u32 = 0x160;

/// The last value written to each of the 32 fogTable registers.
fn trace_fog_registers(name: &str) -> [u32; 32] {
    let mut regs = [0u32; 32];
    for op in trace(name) {
        if let Op::W(a, v) = op {
            if (FOG_TABLE..FOG_TABLE + 0x80).contains(&a) {
                regs[((a - FOG_TABLE) / 4) as usize] = v;
            }
        }
    }
    regs
}

fn check(name: &str, density: f32) {
    let theirs = trace_fog_registers(name);
    let mut table = [0u8; FOG_TABLE_SIZE];
    fog_generate_exp(&mut table, density);
    // The entries themselves (bits 15:8 and 31:24 of each register).
    let entries: Vec<u8> = theirs
        .iter()
        .flat_map(|&v| [(v >> 8) as u8, (v >> 24) as u8])
        .collect();
    let bad: Vec<String> = (0..FOG_TABLE_SIZE)
        .filter(|&i| table[i] != entries[i])
        .map(|i| format!("#{i}: ours {} trace {}", table[i], entries[i]))
        .collect();
    assert!(bad.is_empty(), "{name} fog entries differ: {bad:?}");
    // And the register words grFogTable packs (entries plus deltas).
    let rec = Rec::default();
    let mut g = Glide::init(Box::new(rec.clone()), BoardInfo::new(4, 1, 4));
    let before = rec.0.borrow().len();
    g.fog_table(&table);
    let ours: Vec<Op> = rec.0.borrow()[before..].to_vec();
    let expected: Vec<Op> = (0..32)
        .map(|i| Op::W(FOG_TABLE + 4 * i as u32, theirs[i]))
        .collect();
    assert_eq!(ours, expected, "{name} fogTable registers");
}

#[test]
fn test08_exp_001() {
    check("test08", 0.01);
}

#[test]
fn test22_exp_02() {
    check("test22", 0.2);
}

#[test]
fn test24_exp_09() {
    check("test24", 0.9);
}
