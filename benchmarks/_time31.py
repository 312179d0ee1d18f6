import sys, time, models, sympy as sp
from rigidkin.report.text import problem_text
name = sys.argv[1]
s = getattr(models, name)()
T = time.process_time
t0 = T(); sol = s.solve(); t1 = T()
r = sol.regimes[0]
out = {"derive": t1 - t0}
for what in ("mf", "acc", "react", "eom", "validity", "text"):
    a = T()
    if what == "mf": x = (r.mass_matrix, r.forcing)
    elif what == "acc": x = dict(r.accelerations)
    elif what == "react": x = dict(r.reactions)
    elif what == "eom": x = r.eom
    elif what == "validity": x = r.validity
    else: x = problem_text(sol)
    out[what] = T() - a
    if what in ("acc", "react"): print(what, {str(k): sp.count_ops(v) for k, v in x.items()})
    if what == "text": print("text chars", len(x))
print(name, {k: round(v, 2) for k, v in out.items()}, "total", round(sum(out.values()), 2))
