//! What a bench run reports besides its table: the machine it ran on (with
//! the clock measured) and the rows as JSON.

use std::fmt::Write as _;
use std::time::Instant;

use shadelab_core::SimdLevel;

use super::{BenchArgs, Row};

/// What the numbers were measured on.
pub(super) struct Machine {
    pub(super) cpu: String,
    pub(super) cores: usize,
    pub(super) simd: &'static str,
    /// The core clock while running, measured.
    pub(super) clock_mhz: f64,
    /// A cache line's round trip between two threads, in nanoseconds
    /// (`None` with one core): see `cores.rs`.
    pub(super) round_trip_ns: Option<f64>,
}

impl Machine {
    /// This machine, with the SIMD level the rows run at.
    pub(super) fn detect(simd: SimdLevel) -> Machine {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|text| {
                text.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, name)| name.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Machine {
            cpu,
            cores,
            simd: simd.name(),
            clock_mhz: measure_clock_mhz(),
            round_trip_ns: super::cores::round_trip_ns(cores),
        }
    }
}

/// The clock of the core this runs on, in MHz, estimated from the time a
/// chain of dependent steps `x = x·x + 1` takes: one 64-bit multiplication
/// and one addition, 3 + 1 cycles of latency on x86-64 processors since
/// 2008 (Intel Nehalem, AMD Zen) and on 64-bit Arm cores. Each step needs
/// the one before, so neither the processor nor the compiler can overlap
/// or fold them. The fastest of 20 runs of about a millisecond is kept: on
/// a shared or virtual machine a run can only be slowed down (preempted),
/// never sped up.
pub(super) fn measure_clock_mhz() -> f64 {
    const STEPS: u64 = 1 << 20;
    const CYCLES_PER_STEP: f64 = 4.0;
    let mut best = f64::INFINITY;
    for _ in 0..20 {
        let mut x = std::hint::black_box(3u64);
        let start = Instant::now();
        for _ in 0..STEPS {
            x = x.wrapping_mul(x).wrapping_add(1);
        }
        std::hint::black_box(x);
        best = best.min(start.elapsed().as_secs_f64());
    }
    STEPS as f64 * CYCLES_PER_STEP / best / 1e6
}

/// A JSON string literal.
pub(super) fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Milliseconds as a JSON array's items, to the microsecond.
fn frame_ms(times: &[f64]) -> String {
    let items: Vec<String> = times.iter().map(|t| format!("{t:.4}")).collect();
    items.join(",")
}

pub(super) fn json(machine: &Machine, args: &BenchArgs, rows: &[Row]) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "{{\"machine\":{{\"cpu\":{},\"cores\":{},\"simd\":{},\"clock_mhz\":{:.0},\"round_trip_ns\":{}}},\"warmup\":{},\"warmup_s\":{},\"frames\":{},\"rows\":[",
        quote(&machine.cpu),
        machine.cores,
        quote(machine.simd),
        machine.clock_mhz,
        machine
            .round_trip_ns
            .map_or_else(|| "null".to_string(), |ns| format!("{ns:.0}")),
        args.warmup,
        args.warmup_time,
        args.frames
    );
    for (i, r) in rows.iter().enumerate() {
        if i > 0 {
            s.push(',');
        }
        let _ = write!(
            s,
            "{{\"model\":{},\"triangles\":{},\"width\":{},\"height\":{},\"shading\":{},\"rasterizer\":{},\"threads\":{},\"frames\":{},\"median_ms\":{:.4},\"min_ms\":{:.4},\"covered_pixels\":{},\"fragments\":{},\"mpixels_per_s\":{:.2},\"mtriangles_per_s\":{:.3},\"cycles_per_pixel\":{:.2},\"frame_ms\":[{}]}}",
            quote(r.model),
            r.triangles,
            r.width,
            r.height,
            quote(r.shading.name()),
            quote(r.rasterizer.name()),
            r.threads,
            r.frame_ms.len(),
            r.median_ms,
            r.min_ms,
            r.covered_pixels,
            r.fragments,
            r.mpixels_per_s(),
            r.mtriangles_per_s(),
            r.cycles_per_pixel(machine.clock_mhz),
            frame_ms(&r.frame_ms)
        );
    }
    s.push_str("]}");
    s
}
