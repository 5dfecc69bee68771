"""Where the points of a run go besides memory: AUTO's b., s. and d. files and the screen.

Sinks are attached to a run (`washer.cont.runner.execute(..., sinks=[...])`),
never required: a run in memory is a `Branch`, and files are one more sink.
Each sink receives

    begin(run)                  the run is set up (constants, settings, system)
    branch_start(br)            a new branch (numbered br) begins
    point(lab, point)           a written point (washer.cont.record.Record) and the
                                converged point it was made from (washer.cont.branch.Point)
    note(br, pt, text)          a diagnostic line ("NOTE:Retrying step" ...)
    end(status, elapsed)        the run is over (status "ok" or a reason)

File writing follows AUTO's io.f90 (STHD, WRLINE, WRTSP8, PRINTEIG) through
`washer.auto.files`, which holds the formats; no numerics here.
"""
from __future__ import annotations

import sys

from washer.auto.files import OutputFiles, fmt_es, screen_heading
from washer.cont.codes import type_name


#: AUTO's LBTYPE of a curve type (ITPST), the header's 'Branch type' name.
LBTYPE = {1: "BP", 2: "LP", 3: "HB", 5: "LP", 6: "BP", 7: "PD", 8: "TR"}


#: A run's files are flushed at most this many seconds apart and at its end (also when it
#: fails or is interrupted): a flush of each file at every point cost a short run of a
#: small problem a tenth of its time; a killed process loses at most this much.
FLUSH_SECONDS = 0.5


class FileSink:
    """AUTO's b., s. and d. files of one run, written point by point; an
    s-record is written before its b-row and the s-file is flushed first, so a
    b-file label always has its record (a restart from it cannot fail after a
    crash)."""

    def __init__(self, folder, name: str, protect=(), flush_seconds: float = FLUSH_SECONDS,
                 fresh_s: str = ""):
        """fresh_s: the `s = '...'` the header names for a run without a restart record
        (AUTO's CLUI passes '/', its marker for constants and solution read from one
        stream, which AUTO-07p's headers of such runs show); "" names the constants' s."""
        self.files = OutputFiles(folder, name, protect=protect, flush_seconds=flush_seconds)
        self.fresh_s = fresh_s

    def begin(self, run) -> None:
        self.run = run
        s, c, sysm = run.settings, run.constants, run.system
        curve = sysm.curve_type
        ndim = sysm.n_eq if s.IPS in (0, 1, -1, 11) else s.NDIM
        internal = {k: getattr(s, k) for k in ("ILP", "ISP", "ISW", "NMX")}
        if getattr(sysm, "n_comp", None) and getattr(sysm, "coll", None) is not None:
            # A collocation system: AUTO's header states its own NDIM, NBC (NDIM periodicity
            # conditions of cycles and their loci) and NINT (the phase and the loci's
            # normalisations), the user's below them.
            ndim = sysm.n_comp
            internal["NBC"] = sysm.n_comp if sysm.nbc is None else sysm.nbc
            internal["NINT"] = sysm.nint
        active = list(getattr(sysm, "header_icp", sysm.free))
        self.files.header(c, ndim, getattr(sysm, "header_npar", s.NPAR), run.titles, curve,
                          LBTYPE.get(curve, ""), irs=run.irs_label, nfpr=len(active), ds=s.DS,
                          dsmin=s.DSMIN, dsmax=s.DSMAX, active=active, internal=internal,
                          s_name=self.fresh_s if self.fresh_s and not run.irs_label else None,
                          homcont=getattr(sysm, "homcont_internal", None))

    def branch_start(self, br: int) -> None:
        self.files.branch_start()

    def point(self, lab, point) -> None:
        files = self.files
        if lab.lab:
            files.record(lab)
        st = lab.stability
        pt = (lab.pt - 1) % 9999 + 1
        # The b-file line: PT negative for stable points; BR negative for periodic
        # solutions (IPS = 2), as AUTO writes them (the s-file keeps BR > 0); the record's
        # values themselves (formatted, never changed).
        b_br, b_pt = -lab.br if lab.ips in (2, 12) else lab.br, -pt if lab.stable else pt
        if st is None:
            files.point_row(b_br, b_pt, lab.code, lab.lab, lab.values)
        elif st.kind == "eigenvalues":
            files.point_row(b_br, b_pt, lab.code, lab.lab, lab.values, (lab.br, pt, st.values))
        else:
            # the Floquet block in the row's own d text (one write)
            files.point_row(b_br, b_pt, lab.code, lab.lab, lab.values,
                            (lab.br, pt, st.values, st.n_stable))
            for note in st.notes:
                files.diag(f"{lab.br:4d}{pt:6d} NOTE:{note}")
        if "l1" in lab.info:
            crit = "supercritical" if lab.info["l1"] < 0 else "subcritical"
            files.diag(f"{lab.br:4d}{pt:6d}         First Lyapunov "
                       f"coefficient:{fmt_es(lab.info['l1'], 14, 5)} ({crit})")

    def note(self, br: int, pt: int, text: str) -> None:
        self.files.diag(f"{br:4d}{pt:6d} {text}")

    def end(self, status: str, elapsed: float) -> None:
        n = self.run.branch.counters
        self.files.diag(f"\n{'=' * 47}\n\n Evaluations: residual {n.residuals}, Jacobian "
                        f"{n.jacobians}, factorisations {n.factorisations}\n"
                        f"\n Total Time {elapsed:12.3E}")
        self.files.close()


class ScreenSink:
    """AUTO's table of labelled points on the terminal (format I4,I6,1X,A3,I5,ES14.5)."""

    def __init__(self, stream=None):
        self.stream = stream or sys.stdout

    def begin(self, run) -> None:
        self.titles = run.titles
        print(f"Starting {run.name} ...", file=self.stream)
        self.headed = False

    def branch_start(self, br: int) -> None:
        self.headed = False

    def point(self, lab, point) -> None:
        if not lab.lab:
            return
        if not self.headed:
            print(f"\n{screen_heading(self.titles)}", file=self.stream)
            self.headed = True
        vals = "".join(f"{v:14.5E}" for v in lab.values[:8])
        pt = (lab.pt - 1) % 9999 + 1
        print(f"{lab.br:4d}{pt:6d} {type_name(lab.code):>3}{lab.lab:5d}{vals}", file=self.stream,
              flush=True)

    def note(self, br, pt, text) -> None:
        # AUTO's notes go to the d-file only; warnings about how the run will go on
        # (a stop value passed where nothing is detected) are shown.
        if text.startswith("WARNING:"):
            print(f"{br:4d}{pt:6d} {text}", file=self.stream, flush=True)

    def end(self, status: str, elapsed: float) -> None:
        if status != "ok":
            print(f"\n{status}", file=sys.stderr)
        print(f"\n Total Time {elapsed:12.3E}", file=self.stream)
