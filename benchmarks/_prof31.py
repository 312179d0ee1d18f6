import sys, time, cProfile, pstats, models
from rigidkin.report.text import problem_text
name = sys.argv[1]; what = sys.argv[2]
s = getattr(models, name)()
sol = s.solve()
r = sol.regimes[0]
pr = cProfile.Profile(); t0 = time.process_time(); pr.enable()
if what == "acc": x = dict(r.accelerations)
elif what == "react": x = dict(r.reactions)
elif what == "mf": x = (r.mass_matrix, r.forcing)
elif what == "eom": x = r.eom
elif what == "text": x = problem_text(sol)
pr.disable(); t1 = time.process_time()
print(name, what, round(t1 - t0, 2), "s")
import sympy as sp
if what in ("acc", "react"): print({k: sp.count_ops(v) for k, v in x.items()})
st = pstats.Stats(pr); st.sort_stats("cumulative").print_callees(r"linear.py:134|algebra.py:81")
