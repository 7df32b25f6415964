//! Run a vibration scene through `raceway::Component`, write the time series and the
//! spectra as CSV, and print the characteristic frequencies with the peaks found.
//!
//! ```text
//! cargo run --release --example vibration -- [scene.toml] [duration_s] [settle_s]
//! ```
//!
//! Default scene: `examples/scenes/6205-outer-spall.toml`. Output: `out/<name>-series.csv`
//! (t, shaft.x, shaft.y, force.x, force.y, film.min_thickness) and `out/<name>-spectrum.csv`
//! (frequency, amplitude spectrum of shaft.y, envelope spectrum of force.y).

use raceway::analysis::{
    amplitude_spectrum, characteristic_marks, envelope_spectrum, find_peaks, Verdict, Window,
    FOUND_OVER_FLOOR, LINE_TOLERANCE,
};
use raceway::component::variables;
use raceway::geometry::kinematics;
use raceway::Component;
use std::io::Write;

fn vr(name: &str) -> u32 {
    variables::by_name(name).expect("variable").vr
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| "examples/scenes/6205-outer-spall.toml".into());
    let duration: f64 = args.get(2).map(|s| s.parse()).transpose()?.unwrap_or(1.0);
    let settle: f64 = args.get(3).map(|s| s.parse()).transpose()?.unwrap_or(0.1);
    let name = std::path::Path::new(&path)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("scene")
        .to_string();
    let text = std::fs::read_to_string(&path)?;
    let mut c = Component::from_text(&text)?;
    let omega = c.get_real(vr("shaft.omega"))?;
    let h = 1e-4; // 10 kHz sampling
    let fs = 1.0 / h;
    let names = [
        "shaft.x",
        "shaft.y",
        "force.x",
        "force.y",
        "film.min_thickness",
    ];
    let vrs: Vec<u32> = names.iter().map(|n| vr(n)).collect();
    let n_settle = (settle / h).round() as usize;
    let n = (duration / h).round() as usize;
    let mut rows: Vec<[f64; 6]> = Vec::with_capacity(n);
    let started = std::time::Instant::now();
    for i in 0..n_settle + n {
        c.do_step(i as f64 * h, h)?;
        if i >= n_settle {
            let mut r = [c.time(), 0.0, 0.0, 0.0, 0.0, 0.0];
            for (k, v) in vrs.iter().enumerate() {
                r[k + 1] = c.get_real(*v)?;
            }
            rows.push(r);
        }
    }
    let wall = started.elapsed().as_secs_f64();
    std::fs::create_dir_all("out")?;
    // Written under a temporary name and renamed: never half-written.
    let path = format!("out/{name}-series.csv");
    raceway::fsutil::write_atomic_with(std::path::Path::new(&path), |tmp| {
        let mut f = std::io::BufWriter::new(std::fs::File::create(tmp)?);
        writeln!(f, "t_s,{}", names.join(","))?;
        for r in &rows {
            writeln!(f, "{},{},{},{},{},{}", r[0], r[1], r[2], r[3], r[4], r[5])?;
        }
        f.flush()
    })?;
    let y: Vec<f64> = rows.iter().map(|r| r[2]).collect();
    let fy: Vec<f64> = rows.iter().map(|r| r[4]).collect();
    let spec = amplitude_spectrum(&y, fs, Window::Hann);
    let env = envelope_spectrum(&fy, fs, Some((500.0, 4500.0)));
    let path = format!("out/{name}-spectrum.csv");
    raceway::fsutil::write_atomic_with(std::path::Path::new(&path), |tmp| {
        let mut f = std::io::BufWriter::new(std::fs::File::create(tmp)?);
        writeln!(f, "f_hz,shaft_y_amp_m,force_y_envelope_amp_n")?;
        for k in 0..spec.freq.len() {
            writeln!(f, "{},{},{}", spec.freq[k], spec.amp[k], env.amp[k])?;
        }
        f.flush()
    })?;
    let kin = kinematics(c.bearing(), omega);
    let shaft_hz = omega / (2.0 * std::f64::consts::PI);
    println!(
        "{name}: {duration} s simulated after {settle} s settling in {wall:.2} s wall; resolution {:.2} Hz",
        spec.resolution()
    );
    println!(
        "fs {shaft_hz:.2} Hz  FTF {:.2}  BPFO {:.2}  BPFI {:.2}  BSF {:.2}  2BSF {:.2}",
        kin.ftf,
        kin.bpfo,
        kin.bpfi,
        kin.bsf,
        2.0 * kin.bsf
    );
    let marks = characteristic_marks(&kin, shaft_hz, 3, 1);
    let tol = LINE_TOLERANCE;
    // One rule for "found" (raceway::analysis::find_peaks, shared with `raceway run`): a
    // local maximum (interpolated) within ±min(1 bin, 2 % of the line) at least
    // FOUND_OVER_FLOOR times the median floor, and the line resolved from its neighbours
    // at this record length.
    println!(
        "found: a peak within ±min({:.2} Hz, {:.0} % of f) at least {FOUND_OVER_FLOOR} x the floor (median in [f/2, 2f]); record {:.3} s",
        spec.resolution(),
        100.0 * tol,
        1.0 / spec.resolution()
    );
    println!(
        "{:<16} {:>10} | {:>10} {:>12} {:>7} | {:>10} {:>12} {:>7}",
        "mark", "expected", "shaft.y", "amp (m)", "/floor", "envelope", "amp (N)", "/floor"
    );
    let shown = |p: &raceway::analysis::FoundPeak| match p.verdict {
        Verdict::Found => format!("{:.2}", p.found),
        Verdict::BelowFloor => "-".to_string(),
        Verdict::OffLine => format!("off ({:.2})", p.found),
        Verdict::Unresolved { .. } => "unresolved".to_string(),
        Verdict::AboveNyquist { .. } => "above Nyquist".to_string(),
    };
    for (a, b) in find_peaks(&spec, &marks, tol)
        .iter()
        .zip(find_peaks(&env, &marks, tol))
    {
        println!(
            "{:<16} {:>10.2} | {:>10} {:>12.3e} {:>7.1} | {:>10} {:>12.3e} {:>7.1}",
            a.label,
            a.expected,
            shown(a),
            a.amplitude,
            a.over_floor,
            shown(&b),
            b.amplitude,
            b.over_floor
        );
    }
    println!("wrote out/{name}-series.csv and out/{name}-spectrum.csv");
    Ok(())
}
