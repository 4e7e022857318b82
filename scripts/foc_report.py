#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The closed FOC current loop in `make report` (issue 30 items 3, 4): its runs, table, plots and docs section.

Runs (``POINTS``, kind "foc" of tb/cocotb/demo/demo_runs.py; the loop: tb/cocotb/foc_loop.py): the 400 W 48 V
servo PMSM (svpwm_model.pmsm) held at two speeds, 1000 rpm (m ~ 0.35 at rated current) and 3300 rpm
(m ~ 0.95: the back-EMF takes most of the bus; the low sides' window at the valley, where the shunts are
sampled, shrinks to about a microsecond and closes with a dead time), each with dead time 0, 1 us and 1 us
with the core's compensation (dtc_en_i, the signs from the sampled currents, no hysteresis), and 1 us with
compensation and the signs of the sampled current vector turned to the centre of the pulses the update
produces (foc_loop's "advanced": the same measured currents, 2P later in angle); i_q 0 -> rated (1 ms) ->
-rated; the steady
window (one electrical revolution at 1000 rpm, two at 3300 rpm) at +rated current.  A load step (free
shaft, rated load torque removed at 3 ms, 1 us + compensation).  The isign hysteresis band 1, 2, 5 % of rated
current at the 1000 rpm, 1 us + compensation point (band 0: that run itself), and bands 0 ... 5 % with
white ADC noise of 1 % of rated current rms on every sample.

``summary(results)`` (the figures, from the runs' JSON), ``table(sm)`` (markdown), ``plots(out, sm)``
(fig_foc_*.png), ``write_docs(sm)``: the generated section of docs/demo.md between the markers
``<!-- foc:begin -->`` / ``<!-- foc:end -->`` (``python scripts/foc_report.py [build/report] --docs``;
never typed by hand).
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DOCS = REPO / "docs" / "demo.md"
BEGIN, END = "<!-- foc:begin -->", "<!-- foc:end -->"
P = 1536
TS = 2 * P / 48e6
DT_1US = 48

# the speeds: (tag, rpm, steady window start (s), electrical revolutions, -rated step (s), end (s))
SPEEDS = (("n1000", 1000.0, 0.003, 1, 0.0185, 0.023), ("n3300", 3300.0, 0.003, 2, 0.0125, 0.017))
CASES = (("dt0", 0, 0, "dead time 0", {}), ("dt1us", DT_1US, 0, "1 µs, no compensation", {}),
         ("dt1us_dtc", DT_1US, 1, "1 µs + compensation", {}),
         ("dt1us_dtc_adv", DT_1US, 1, "1 µs + compensation, signs at the pulses' centre", {"isign_from": "advanced"}),
         ("dt1us_dtc_shunts", DT_1US, 1, "1 µs + compensation, low-side shunts (trigger point, window report)",
          {"shunts": {"win_min": 96}}))
# (the shunt runs: the ADC starts at trigger point 0 at the valley (the clock after it) and needs the low side
# on for 1 µs before and after its sample: win_min = 96 clocks at 48 MHz)
HYST = (0.01, 0.02, 0.05)
HYST_AT = "n1000"
NOISE_PU = 0.01          # the hysteresis runs with ADC noise: 1 % of rated current rms (10 codes)


def _pt(name, rpm, steps, t_end, steady, dt, dtc, title, **kw) -> dict:
    return dict(name=name, kind="foc", study="foc", speed_rpm=rpm, period=P, dt=dt, dtc=dtc, iq_steps=steps,
                t_end_s=t_end, steady=steady, title=title, **kw)


def points() -> list[dict]:
    out = []
    for tag, rpm, t_ss, revs, t_neg, t_end in SPEEDS:
        for case, dt, dtc, lab, kw in CASES:
            out.append(_pt(f"foc_{tag}_{case}", rpm, [[0, 0], [0.001, 1.0], [t_neg, -1.0]], t_end, [t_ss, revs],
                           dt, dtc, f"{rpm:.0f} rpm, {lab}", group=tag, case=case, **kw))
    tag, rpm, t_ss, revs, t_neg, t_end = SPEEDS[0]
    noise = NOISE_PU * 14.85 / (60 / 4096)                     # codes rms (Adc12 defaults, rated 14.85 A)
    for nz in (0.0, noise):
        for h in ((0.0,) + HYST) if nz else HYST:
            tail = f"_h{int(round(h * 100)):02d}" + ("_noise" if nz else "")
            out.append(_pt(f"foc_{tag}_dt1us_dtc{tail}", rpm, [[0, 0], [0.001, 1.0]], t_neg, [t_ss, revs], DT_1US,
                           1, f"{rpm:.0f} rpm, 1 µs + compensation, isign band {h:.0%}"
                           + (f", ADC noise {NOISE_PU:.0%} rms" if nz else ""),
                           group="hyst", case=f"h{h}", hyst=h, noise=bool(nz), adc={"noise_lsb": nz} if nz else {}))
    out.append(_pt("foc_load_step", 1000.0, [[0, 0], [0.001, 1.0]], 0.010, None, DT_1US, 1,
                   "1000 rpm, free shaft, rated load removed at 3 ms, 1 µs + compensation", group="load",
                   case="load", fixed_speed=False, load=[[0, 1.27], [0.003, 0.0]]))
    return out


POINTS = points()


def summary(results: list[dict]) -> dict:
    rows, hyst, load = [], [], None
    for r in results:
        pt = r["point"]
        if pt.get("kind") != "foc" or r.get("missing"):
            continue
        m = r["metrics"]
        st = m.get("steady") or {}
        row = dict(name=pt["name"], title=pt["title"], group=pt["group"], case=pt["case"], rpm=pt["speed_rpm"],
                   dt=pt["dt"], dtc=pt["dtc"], hyst=pt.get("hyst", 0.0), noise=pt.get("noise", False), ok=r.get("ok"),
                   rtl_equals_model=r.get("rtl_equals_model"), n_periods=r["n_periods"], sim_wall_s=r["sim_wall_s"],
                   steps=[dict(frm=s["iq_from"], to=s["iq_to"], rise_us=None if s["rise_s"] is None else 1e6 * s["rise_s"],
                               overshoot_pct=s["overshoot_pct"], final_err_pct=s["final_err_pct"]) for s in m["steps"]],
                   i_thd_pct=100 * st["i_thd"] if st else None,
                   id_ripple_rms=st.get("id_ripple_rms"), iq_ripple_rms=st.get("iq_ripple_rms"),
                   iq_mean=st.get("iq_mean"), id_mean=st.get("id_mean"), v_pu_max=st.get("v_pu_max"),
                   v_pu_mean=st.get("v_pu_mean"), pi_limited=st.get("pi_limited_periods"),
                   window_periods=st.get("periods"), lowside_min_clocks=st.get("lowside_window_min_clocks"),
                   sat_periods=r.get("sat_periods"), isign_changes=r.get("isign_changes"), npz=r.get("npz"),
                   shunts=r.get("shunts"))
        if pt["group"] == "load":
            load = row
            import numpy as np
            z = np.load(r["npz"])
            t, iq, ref, rpm = z["t"], z["iq"], z["iq_ref"], z["rpm"]
            after = t >= 0.003
            row.update(load_iq_dev_max=float(np.max(np.abs(iq[after] - ref[after]))),
                       load_iq_dev_last=float(np.mean(iq[t >= t[-1] - 10 * TS] - ref[t >= t[-1] - 10 * TS])),
                       rpm_at_step=float(rpm[np.argmax(after)]), rpm_end=float(rpm[-1]))
        elif pt["group"] == "hyst":
            hyst.append(row)
        else:
            rows.append(row)
    base = {r["name"]: r for r in rows}
    hy = [dict(band_pct=0.0, i_thd_pct=base[f"foc_{HYST_AT}_dt1us_dtc"]["i_thd_pct"], run=f"foc_{HYST_AT}_dt1us_dtc")] \
        if f"foc_{HYST_AT}_dt1us_dtc" in base else []
    noisy = {r["hyst"]: r for r in hyst if r["noise"]}
    hy += [dict(band_pct=100 * r["hyst"], i_thd_pct=r["i_thd_pct"], run=r["name"]) for r in hyst if not r["noise"]]
    for h in hy:
        n = noisy.get(h["band_pct"] / 100)
        h.update(i_thd_noise_pct=n["i_thd_pct"] if n else None, run_noise=n["name"] if n else None)
    verdict = []
    for tag, rpm, *_ in SPEEDS:
        for case in ("dt1us_dtc", "dt1us_dtc_adv"):
            a, b = base.get(f"foc_{tag}_dt0"), base.get(f"foc_{tag}_{case}")
            if a and b and a["i_thd_pct"] is not None and b["i_thd_pct"] is not None:
                d = b["i_thd_pct"] - a["i_thd_pct"]
                verdict.append(dict(rpm=rpm, case=case, title=b["title"], thd_dt0=a["i_thd_pct"],
                                    thd_dtc=b["i_thd_pct"], diff_pp=d, within_0p2pp=abs(d) <= 0.2))
    return dict(rows=rows, hysteresis=hy, load=load, dtc_vs_dt0=verdict,
                definitions="rise: 10-90 % of the step of the true i_q sampled at the valleys (linear "
                            "interpolation), from the period the new reference is first used; overshoot: beyond "
                            "the new reference in % of the step; ripple: rms of i_d, i_q (the motor's continuous "
                            "current in the rotor frame, PWM ripple included) over the steady window at +rated; "
                            "THD: phase a current to the 200th harmonic over whole electrical revolutions of that "
                            "window; |v|: the PI's output / (Udc / sqrt3); PI limited: periods of the window in "
                            "which the PI's output was held at the inscribed circle; low-side window: the shortest "
                            "time a low side is on around the valley (the shunt sample) in that window.")


def _f(x, fmt="{:.2f}"):
    return "—" if x is None else fmt.format(x)


def table(sm: dict) -> list[str]:
    lines = ["| run | rise 0→+rated (µs) | overshoot (%) | rise +→−rated (µs) | overshoot (%) | i_d ripple (A rms) "
             "| i_q ripple (A rms) | i_a THD (%) | max \\|v\\| (pu) | PI limited (periods) | low-side window (clocks) "
             "| RTL == model |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sm["rows"]:
        s = r["steps"] + [dict(rise_us=None, overshoot_pct=None)] * (2 - len(r["steps"]))
        lines.append(f"| {r['title']} | {_f(s[0]['rise_us'], '{:.0f}')} | {_f(s[0]['overshoot_pct'])} | "
                     f"{_f(s[1]['rise_us'], '{:.0f}')} | {_f(s[1]['overshoot_pct'])} | {_f(r['id_ripple_rms'], '{:.3f}')} | "
                     f"{_f(r['iq_ripple_rms'], '{:.3f}')} | {_f(r['i_thd_pct'])} | {_f(r['v_pu_max'], '{:.3f}')} | "
                     f"{_f(r['pi_limited'], '{:d}')} of {_f(r['window_periods'], '{:d}')} | "
                     f"{_f(r['lowside_min_clocks'], '{:d}')} | {'yes' if r['rtl_equals_model'] else 'NO'} |")
    return lines


def shunt_table(sm: dict) -> list[str]:
    """The low-side shunt runs: how often each phase was unreadable and what the loop did."""
    lines = ["| run | periods | phase a / b / c unreadable (periods) | one phase reconstructed | all held (two "
             "unreadable) | i_a THD (%) |", "|---|---|---|---|---|---|"]
    for r in sm["rows"]:
        sh = r.get("shunts")
        if sh:
            lines.append(f"| {r['title']} (win_min {sh['win_min']} clocks) | {sh['periods']} | "
                         f"{' / '.join(str(x) for x in sh['unreadable'])} | {sh['reconstructed']} | {sh['held']} | "
                         f"{_f(r['i_thd_pct'])} |")
    return lines


def hyst_table(sm: dict) -> list[str]:
    lines = [f"| isign band (% of rated) | i_a THD (%), no noise | i_a THD (%), ADC noise {NOISE_PU:.0%} of rated rms |",
             "|---|---|---|"]
    lines += [f"| {h['band_pct']:.0f} | {_f(h['i_thd_pct'])} | {_f(h.get('i_thd_noise_pct'))} |"
              for h in sm["hysteresis"]]
    return lines


def verdict(sm: dict) -> list[str]:
    out = []
    for v in sm["dtc_vs_dt0"]:
        out.append(f"{v['title']}: i_a THD {v['thd_dtc']:.2f} % vs dead time 0 {v['thd_dt0']:.2f} %: "
                   f"{v['diff_pp']:+.2f} percentage points, {'within' if v['within_0p2pp'] else 'NOT within'} 0.2 pp")
    ld = sm.get("load")
    if ld:
        out.append(f"load step (rated load removed, free shaft, {ld['rpm_at_step']:.0f} -> {ld['rpm_end']:.0f} rpm): "
                   f"largest |i_q - ref| {ld['load_iq_dev_max']:.3f} A "
                   f"({100 * ld['load_iq_dev_max'] / 14.85:.1f} % of rated), mean error over the last 10 periods "
                   f"{ld['load_iq_dev_last']:+.3f} A")
    return out


def plots(out: Path, sm: dict) -> list[tuple[str, str, str]]:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    figs = []
    for tag, rpm, t_ss, revs, t_neg, t_end in SPEEDS:
        runs = [r for r in sm["rows"] if r["group"] == tag]
        if not runs:
            continue
        fig, ax = plt.subplots(3, 1, figsize=(10, 9), sharex=False)
        for k, r in enumerate(runs):
            z = np.load(r["npz"])
            col = f"C{k}"
            ax[0].plot(1e3 * z["t"], z["iq"], color=col, label=f"i_q, {r['case']}")
            ax[0].plot(1e3 * z["t"], z["id"], color=col, ls=":", label=f"i_d, {r['case']}")
            tt = z["trace_t"] / 48e6
            sel = (tt >= t_ss) & (tt < t_ss + revs * 60 / rpm / 4)            # p = 4 pole pairs
            ax[1].plot(1e3 * tt[sel], z["trace_i"].real[sel], color=col, lw=0.7, label=f"i_a, {r['case']}")
            zoom = (z["t"] >= 0.0008) & (z["t"] < 0.0008 + 30 * TS)
            ax[2].plot(1e6 * (z["t"][zoom] - 0.001), z["iq"][zoom], color=col, marker=".", label=r["case"])
        z0 = np.load(runs[0]["npz"])
        ax[0].plot(1e3 * z0["t"], z0["iq_ref"], "k--", lw=0.8, label="i_q ref")
        ax[0].set(xlabel="t (ms)", ylabel="A", title=f"{rpm:.0f} rpm: i_q, i_d at the valley samples")
        ax[1].set(xlabel="t (ms)", ylabel="A", title="phase a current (motor model), steady window at +rated")
        ax[2].set(xlabel="µs after the step", ylabel="A", title="the 0 → +rated step")
        for a in ax:
            a.grid(alpha=0.3)
            a.legend(fontsize=7, ncol=3)
        fig.tight_layout()
        fn = f"fig_foc_{tag}.png"
        fig.savefig(out / fn, dpi=110)
        plt.close(fig)
        figs.append((fn, f"FOC current loop, {rpm:.0f} rpm",
                     "i_q steps 0 → +rated → −rated with dead time 0, 1 µs and 1 µs + compensation; the phase "
                     "current in the steady window."))
    ld = sm.get("load")
    if ld:
        z = np.load(ld["npz"])
        fig, ax = plt.subplots(2, 1, figsize=(10, 6))
        ax[0].plot(1e3 * z["t"], z["iq"], label="i_q")
        ax[0].plot(1e3 * z["t"], z["id"], label="i_d")
        ax[0].plot(1e3 * z["t"], z["iq_ref"], "k--", lw=0.8, label="i_q ref")
        ax[1].plot(1e3 * z["t"], z["rpm"], label="speed (rpm)")
        ax[1].plot(1e3 * z["t"], 1000 * z["t_load"], label="load torque (mN m)")
        for a in ax:
            a.grid(alpha=0.3)
            a.legend(fontsize=8)
            a.set_xlabel("t (ms)")
        fig.tight_layout()
        fig.savefig(out / "fig_foc_load.png", dpi=110)
        plt.close(fig)
        figs.append(("fig_foc_load.png", "FOC current loop, load step",
                     "Free shaft at 1000 rpm and rated current; the rated load torque is removed at 3 ms."))
    return figs


def section(sm: dict) -> list[str]:
    lines = [BEGIN, "", "Generated by `python scripts/foc_report.py --docs` from the runs of `make report` "
             "(build/report/demo.json); do not edit by hand.", ""]
    lines += table(sm) + [""]
    lines += ["Low-side shunts (issue 30 item 2: the ADC at trigger point 0, the core's window report deciding "
              "which phases to read and which to reconstruct):", ""] + shunt_table(sm) + [""]
    lines += ["isign_i hysteresis at the 1000 rpm, 1 µs + compensation steady point (issue 30 item 4):", ""]
    lines += hyst_table(sm) + [""]
    lines += [f"- {x}" for x in verdict(sm)] + ["", "Definitions: " + sm["definitions"], "", END]
    return lines


def write_docs(sm: dict, path: Path = DOCS) -> None:
    text = path.read_text()
    new = "\n".join(section(sm))
    if BEGIN in text and END in text:
        a, b = text.index(BEGIN), text.index(END) + len(END)
        text = text[:a] + new + text[b:]
    else:
        text = text.rstrip("\n") + "\n\n## Closed FOC current loop (issue 30 item 3)\n\n" + new + "\n"
    path.write_text(text)


def append_report(out: Path, sm: dict, figs) -> None:
    rep = out / "report.md"
    lines = ["", "## Closed FOC current loop (PMSM, ADC, dq PI, RTL in the loop)", ""]
    lines += table(sm) + ["", "Low-side shunts:", ""] + shunt_table(sm)
    lines += ["", "isign_i hysteresis (1000 rpm, 1 µs + compensation):", ""] + hyst_table(sm)
    lines += [""] + [f"- {x}" for x in verdict(sm)] + ["", "Definitions: " + sm["definitions"], ""]
    for fn, title, text in figs:
        lines += [f"### {title}", "", f"![{title}]({fn})", "", text, ""]
    with open(rep, "a") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", nargs="?", type=Path, default=REPO / "build" / "report")
    ap.add_argument("--docs", action="store_true", help=f"rewrite the generated section of {DOCS.relative_to(REPO)}")
    args = ap.parse_args()
    d = json.loads((args.out / "demo.json").read_text())
    sm = summary(d["results"])
    print("\n".join(table(sm) + [""] + shunt_table(sm) + [""] + hyst_table(sm) + [""] + verdict(sm)))
    if args.docs:
        write_docs(sm)
        print(f"wrote {DOCS}")
    sys.exit(0)
