# %% [markdown]
# # Plan, check and plot a mission with shoal from Python
#
# The paper's experiment (the embedded default scenario: one USV and N = 5 AUVs over a
# synthetic seafloor, one window of K = 20 steps of 100 s), planned by Algorithm 1, verified
# by the library's independent checker, and drawn with matplotlib: the tracks over the floor
# (plan view) and each AUV's depth against the floor beneath it (depth profile).
#
# Run it as a script (`python examples/python/plan_and_plot.py [OUT.png]`) or cell by cell
# in an editor that knows `# %%` cells (VS Code, Spyder, Jupytext).

# %%
import sys

import matplotlib

if "ipykernel" not in sys.modules:
    matplotlib.use("Agg")  # a script writes the PNG; a notebook shows the figure inline
import matplotlib.pyplot as plt
import numpy as np

import shoal

out = sys.argv[1] if len(sys.argv) > 1 and not sys.argv[1].startswith("-") else "plan_and_plot.png"

# %% [markdown]
# ## Plan
# `shoal.plan` takes the scenario ("default", a TOML file or a dict of its keys) and
# releases the GIL while it plans. The arrays cover every step of the mission.

# %%
plan = shoal.plan("default")
print(plan)
print("AUV positions:", plan.positions.shape, "(steps, N, 3)")

# %% [markdown]
# ## Check
# The checker re-evaluates every constraint from the plan and the floor alone.

# %%
report = plan.check()
for family in report.violations:
    print("FAIL", family.name, family.worst_margin, family.unit, family.where)
print("check:", "every constraint holds" if report.passed else "VIOLATED")

# %% [markdown]
# ## Metrics

# %%
for name, value in plan.metrics.items():
    print(f"  {name:<22} {value:.4g}")

# %% [markdown]
# ## Plot
# Left: plan view, the floor's heights (metres) under the USV's and the AUVs' tracks.
# Right: each AUV's depth and the floor beneath it along the mission.

# %%
x, y, z = plan.seafloor()
pos, usv, t = plan.positions, plan.usv_positions, plan.times
pad = 400.0
xs = np.concatenate([pos[..., 0].ravel(), usv[:, 0]])
ys = np.concatenate([pos[..., 1].ravel(), usv[:, 1]])
ix = (x >= xs.min() - pad) & (x <= xs.max() + pad)
iy = (y >= ys.min() - pad) & (y <= ys.max() + pad)


def floor_at(px, py):
    """The floor's height under (px, py): bilinear between the grid's nodes."""
    fi = (px - x[0]) / (x[1] - x[0])
    fj = (py - y[0]) / (y[1] - y[0])
    i = np.clip(np.floor(fi).astype(int), 0, len(x) - 2)
    j = np.clip(np.floor(fj).astype(int), 0, len(y) - 2)
    u, v = fi - i, fj - j
    return ((1 - u) * (1 - v) * z[j, i] + u * (1 - v) * z[j, i + 1]
            + (1 - u) * v * z[j + 1, i] + u * v * z[j + 1, i + 1])


fig, (ax_map, ax_depth) = plt.subplots(1, 2, figsize=(13, 5.5), constrained_layout=True)
filled = ax_map.contourf(x[ix], y[iy], z[np.ix_(iy, ix)], levels=20, cmap="Blues_r")
fig.colorbar(filled, ax=ax_map, label="seafloor height z (m)")
ax_map.plot(usv[:, 0], usv[:, 1], "k-", lw=2.5, label="USV")
ax_map.plot(usv[0, 0], usv[0, 1], "ko")
for n in range(plan.auvs):
    line, = ax_map.plot(pos[:, n, 0], pos[:, n, 1], "-", lw=1.5, label=f"AUV {n}")
    ax_map.plot(pos[0, n, 0], pos[0, n, 1], "o", color=line.get_color())
    depth = ax_depth.plot(t, pos[:, n, 2], "-", color=line.get_color(), label=f"AUV {n}")
    ax_depth.plot(t, floor_at(pos[:, n, 0], pos[:, n, 1]), ":", color=line.get_color())
ax_map.set(xlabel="x east (m)", ylabel="y north (m)", aspect="equal",
           title=f"plan view: N = {plan.auvs}, {plan.windows} window(s), seed {plan.seed}")
ax_map.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=plan.auvs + 1, fontsize=8)
ax_depth.set(xlabel="time (s)", ylabel="z (m)",
             title="depth profile: AUVs (solid) and the floor beneath them (dotted)")
ax_depth.legend(loc="best", fontsize=8)
fig.savefig(out, dpi=110)
print("wrote", out)
