"""A small fault-signature data set: defect size × location × speed → vibration series + labels.

Each case is a 6205 at the ring level (study [4]'s test-rig set-up, as
examples/scenes/6205-outer-spall.toml: inner ring load-driven under 1000 N downward with
1 kg of shaft, 10 µm clearance, contact damping) carrying one local defect (docs/physics.md
§5.3: a spall of the given width on the outer race, the inner race or one ball), or none (the
healthy reference). ``raceway.run`` integrates it; the cases run on two threads (the package
releases the GIL). Written:

- ``series/<id>.csv``: ``t [s]``, ``shaft.x [m]``, ``shaft.y [m]``, ``force.x [N]``,
  ``force.y [N]`` (the ring's vibration and the bearing force), sampled at 10 kHz;
- ``labels.csv``: one row per case: id, location, width, depth, speed, load and the
  characteristic frequencies the library expects (shaft, FTF, BSF, BPFO, BPFI, 2 BSF) with
  the defect's own line;
- a figure of the envelope spectra with the expected lines marked.

Envelope analysis (Randall & Antoni, *Mech. Syst. Signal Process.* 25 (2011) §4), done here
in numpy the way ``raceway run`` does it for a defect scene: the ring's ``shaft.y`` over the
second half of the run (past the start), band-passed from three times the highest defect
frequency to 0.8 of the Nyquist frequency, its Hilbert envelope, the Hann-windowed amplitude
spectrum of that. Check (CI): for every defect case the envelope spectrum's highest line within half the
cage frequency (FTF) of the defect's characteristic frequency (BPFO, BPFI, or 2 BSF for a
ball, which strikes both races once per spin and whose line carries FTF side bands) lies
within one bin of it and stands at least 4 times over the median of the spectrum in
[f/2, 2f], and the library's own envelope analysis (the run summary's
``envelope_frequencies``) found that line within a bin of the same place.

    python examples/python/sweeps/fault_dataset.py --quick
    python examples/python/sweeps/fault_dataset.py --write-docs
"""

from __future__ import annotations

import csv
import itertools
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import raceway
from common import arguments, check, figure_path, load_average, pyplot, save

LOAD_N = 1000.0
DEPTH_UM = 30.0
STEP_S = 1e-4
# The line each location's defect strikes at (labels of the library's summary).
DEFECT_LINE = {"outer": "1xBPFO", "inner": "1xBPFI", "ball": "1x2BSF"}
MARKS = {"fs": "shaft", "FTF": "FTF", "BSF": "BSF", "1xBPFO": "BPFO", "1xBPFI": "BPFI", "1x2BSF": "2 BSF"}


def scene(location: str, width_mm: float, rpm: float, duration: float) -> dict:
    """The case's scene; ``location`` ``"none"``: no defect."""
    s = {
        "title": f"6205, {location} defect {width_mm:g} mm, {rpm:g} rpm",
        "bearing": {"preset": "6205", "clearance_um": 10.0},
        "model": {"level": "ring", "causality": "load", "ring_dof": 2, "contact_damping": 200.0, "attached_mass_kg": 1.0},
        # The shipped spall scene's settings: a force error of at most 1e-4 against rtol
        # 1e-9, by the error control alone (no sub-step cap; docs/speed.md).
        "solver": {"rtol": 1e-7, "atol_m": 1e-11},
        "inputs": {"rule": "hold", "speed_rpm": rpm, "initial": {"load.y": -LOAD_N}},
        "run": {"duration_s": duration, "step_s": STEP_S},
    }
    if location != "none":
        defect = {"race": location, "angle_deg": 270.0, "width_mm": width_mm, "depth_um": DEPTH_UM}
        if location == "ball":
            defect["ball"] = 0
            defect["angle_deg"] = 0.0
        s["effects"] = {"defects": [defect]}
    return s


def envelope_spectrum(x: np.ndarray, fs: float, band: tuple[float, float]) -> tuple[np.ndarray, np.ndarray]:
    """Amplitude spectrum (Hann, single-sided, coherent gain corrected) of the Hilbert
    envelope of ``x`` band-passed to ``band`` Hz (analytic signal by FFT: negative
    frequencies removed, positive doubled)."""
    n = len(x)
    xf = np.fft.fft(x - x.mean())
    f = np.fft.fftfreq(n, 1.0 / fs)
    h = np.where((f > 0) & (f >= band[0]) & (f <= band[1]), 2.0, 0.0)
    env = np.abs(np.fft.ifft(xf * h))
    w = np.hanning(n)
    amp = np.abs(np.fft.rfft((env - env.mean()) * w)) * 2.0 / w.sum()
    return np.fft.rfftfreq(n, 1.0 / fs), amp


def analyse(series, summary) -> dict:
    """The case's expected lines (from the library) and its envelope spectrum."""
    lines = {f["label"]: f["expected [Hz]"] for f in summary["frequencies"]}
    # The library's own envelope analysis of the same signal (raceway run's summary).
    found = {f["label"]: f["found [Hz]"] for f in summary.get("envelope_frequencies", [])}
    y = series["shaft.y [m]"].to_numpy()
    y = y[len(y) // 2 :]
    fs = 1.0 / STEP_S
    top = max(lines["1xBPFO"], lines["1xBPFI"], lines["1x2BSF"])
    f, amp = envelope_spectrum(y, fs, (3.0 * top, 0.8 * fs / 2))
    return {"lines": lines, "found": found, "f": f, "amp": amp}


def peak_near(f: np.ndarray, amp: np.ndarray, f0: float, half_width: float) -> tuple[float, float]:
    """Frequency of the highest envelope line within ``f0 ± half_width`` and its height over
    the median of the spectrum in [f0/2, 2 f0] (the floor ``raceway run`` judges against)."""
    sel = (f >= f0 - half_width) & (f <= f0 + half_width)
    i = np.argmax(amp[sel])
    floor = np.median(amp[(f >= f0 / 2) & (f <= 2 * f0)])
    return float(f[sel][i]), float(amp[sel][i] / floor)


def plot(path, cases, results, rpm, width):
    plt = pyplot()
    shown = [c for c in cases if c[1] == rpm and c[2] in (width, 0.0)]
    fig, axes = plt.subplots(len(shown), 1, figsize=(10, 2.3 * len(shown) + 0.8), sharex=True, constrained_layout=True)
    styles = {"fs": ("k", ":"), "FTF": ("tab:brown", ":"), "BSF": ("tab:purple", ":"), "1xBPFO": ("tab:red", "--"), "1xBPFI": ("tab:green", "--"), "1x2BSF": ("tab:orange", "--")}
    for ax, case in zip(np.atleast_1d(axes), shown):
        r = results[case]
        sel = r["f"] <= 400.0
        ax.plot(r["f"][sel], r["amp"][sel] * 1e9, color="tab:blue", lw=1)
        for label, (colour, ls) in styles.items():
            ax.axvline(r["lines"][label], color=colour, ls=ls, lw=1.2, label=MARKS[label])
        loc = case[0]
        ax.set_title(f"{loc} defect, {case[2]:g} mm wide" if loc != "none" else "healthy", fontsize=10, loc="left")
        ax.set_ylabel("envelope [nm]")
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("frequency [Hz]")
    axes[0].legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, title="expected lines")
    fig.suptitle(f"6205 at {rpm:g} rpm, {LOAD_N:g} N: envelope spectra of the ring's vertical motion (band {results[shown[0]]['band']})")
    save(fig, path)


def main() -> None:
    args = arguments("fault_dataset", __doc__)
    if args.quick:
        locations, widths, speeds, duration = ["outer", "inner", "ball"], [1.0], [1750.0], 1.0
    else:
        locations, widths, speeds, duration = ["outer", "inner", "ball"], [0.5, 1.0, 1.5], [1200.0, 1750.0, 2400.0], 1.0
    cases = [(loc, n, w) for loc, w, n in itertools.product(locations, widths, speeds)]
    cases += [("none", n, 0.0) for n in speeds]
    with ThreadPoolExecutor(max_workers=2) as pool:
        runs = list(pool.map(lambda c: raceway.run(scene(c[0], c[2], c[1], duration)), cases))
    cpu = sum(s["cpu [s]"] for _, s in runs)
    print(f"{len(cases)} cases of {duration:g} s: the runs' thread CPU time {cpu:.2f} s (load average {load_average()})")

    series_dir = args.out / "series"
    series_dir.mkdir(exist_ok=True)
    results = {}
    with open(args.out / "labels.csv", "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["id", "location", "width [mm]", "depth [µm]", "speed [rpm]", "load [N]", "shaft [Hz]", "FTF [Hz]", "BSF [Hz]", "BPFO [Hz]", "BPFI [Hz]", "2BSF [Hz]", "defect_line", "defect [Hz]", "file"])
        for i, (case, (series, summary)) in enumerate(zip(cases, runs)):
            loc, rpm, width = case
            r = analyse(series, summary)
            top = max(r["lines"][k] for k in DEFECT_LINE.values())
            r["band"] = f"{3 * top:.0f}–{0.8 * 0.5 / STEP_S:.0f} Hz"
            results[case] = r
            name = f"series/{i:03d}.csv"
            series[["t [s]", "shaft.x [m]", "shaft.y [m]", "force.x [N]", "force.y [N]"]].to_csv(args.out / name, index=False)
            line = DEFECT_LINE.get(loc)
            ls = r["lines"]
            out.writerow([i, loc, width, DEPTH_UM if line else 0.0, rpm, LOAD_N, ls["fs"], ls["FTF"], ls["BSF"], ls["1xBPFO"], ls["1xBPFI"], ls["1x2BSF"], line or "", ls[line] if line else "", name])
    plot(figure_path(args, "envelope"), cases, results, speeds[len(speeds) // 2], widths[len(widths) // 2])

    for case, r in results.items():
        loc, rpm, width = case
        if loc == "none":
            continue
        f0 = r["lines"][DEFECT_LINE[loc]]
        bin_hz = r["f"][1]
        # Between the neighbouring cage-frequency side bands (a ball's defect enters and
        # leaves the load zone once per cage turn, so 2 BSF carries FTF side bands).
        fp, height = peak_near(r["f"], r["amp"], f0, r["lines"]["FTF"] / 2)
        lib = r["found"].get(DEFECT_LINE[loc])
        check(
            abs(fp - f0) <= bin_hz and height >= 4.0 and lib is not None and abs(lib - fp) <= bin_hz,
            f"{loc} defect {width:g} mm at {rpm:g} rpm: envelope peak {fp:.1f} Hz, {height:.0f} x the floor; "
            f"expected {MARKS[DEFECT_LINE[loc]]} {f0:.1f} Hz (bin {bin_hz:.1f} Hz); the library's envelope analysis: "
            + (f"{lib:.1f} Hz" if lib is not None else "not found"),
        )


if __name__ == "__main__":
    main()
