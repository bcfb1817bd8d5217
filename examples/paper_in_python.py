"""The paper's preset from Python: load it, change the speed, run, plot the
contact forces, and set the identified modes beside the ring's own.

    python examples/paper_in_python.py [--speed 15] [-o paper_in_python.png]
"""

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import tirecontact as tc

HERE = Path(__file__).resolve().parent


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=15.0, help="rolling speed (m/s)")
    ap.add_argument("-o", "--output", default="paper_in_python.png", help="figure (PNG)")
    a = ap.parse_args(argv)

    scene = tc.Scene.load(HERE.parent / "presets" / "paper.ron")
    scene.set("speed_mps", a.speed)
    run = tc.run(scene)
    model = tc.identify(scene)

    fig, (ax_q, ax_g) = plt.subplots(2, 1, figsize=(10, 8), constrained_layout=True)
    # the last three road periods
    period_s = 0.1 / a.speed
    shown = run.t_s >= run.t_s[-1] - 3 * period_s
    for i in range(scene.num_points):
        ax_q.plot(run.t_s[shown] * 1e3, run.q_n[shown, i], lw=1.2, label=f"point {i}")
    # impacts are impulses, drawn as impulse / dt (one sample each): the
    # axis is fitted to the rolling force and the spikes clipped
    q = run.q_n[shown]
    rolling = np.percentile(q[q > 0], 97)
    ax_q.set_ylim(-0.05 * rolling, 1.35 * rolling)
    ax_q.set_xlabel("time (ms)")
    ax_q.set_ylabel("contact force (N)")
    ax_q.set_title(
        f"{a.speed:g} m/s, last three road periods (impact spikes, impulse / dt, clipped)"
    )
    ax_q.legend(ncol=5, loc="upper right", fontsize=9)

    f = np.linspace(1.0, 500.0, 2000)
    g = np.abs(model.frf(f)[:, 2, 2])
    ax_g.semilogy(f, g, color="k", lw=1.2, label="identified model, |G₂₂|")
    for k, fk in enumerate(model.freq_hz):
        ax_g.axvline(fk, color="tab:orange", lw=0.8, alpha=0.7, label="identified modes" if k == 0 else None)
    ax_g.set_xlabel("frequency (Hz)")
    ax_g.set_ylabel("|G| at the centre point (m/N)")
    r = model.report
    ax_g.set_title(
        f"{len(model.freq_hz)} modes identified by LSCE over {r['band_hz'][0]:g}-{r['band_hz'][1]:g} Hz; "
        f"|G| error against the ring {r['magnitude_error']:.1%}"
    )
    ax_g.legend(loc="lower left", fontsize=9)
    fig.savefig(a.output, dpi=110)
    print(
        f"wrote {a.output}: {run.stats['steps']} steps in {run.stats['wall_s']:.3f} s, "
        f"{len(model.freq_hz)} modes {model.freq_hz.min():.1f}-{model.freq_hz.max():.1f} Hz"
    )


if __name__ == "__main__":
    main()
