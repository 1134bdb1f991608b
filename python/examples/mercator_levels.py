# SPDX-License-Identifier: GPL-3.0-or-later
"""The README's Python example: the Mercator mesh and its mask stage, drawn with matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/mercator_levels.py docs/images/python_mercator.png
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
import numpy as np

import aquatoria as aq

run = aq.mesh("configs/global_mercator.toml", {"quadtree.size_km": 110})
print(run, "; min depth", run.depth.min(), "m; boundaries", len(run.boundaries))

# The North Atlantic: triangles whose corners all lie in the box, coloured by quadtree level.
lon, lat = run.nodes[:, 0], run.nodes[:, 1]
box = (lon > -80) & (lon < 0) & (lat > 0) & (lat < 70)
keep = box[run.triangles].all(axis=1)
tri = mtri.Triangulation(lon, lat, run.triangles[keep])

mask = aq.mask("configs/global_mercator.toml", {"quadtree.size_km": 110})

fig, (a, b) = plt.subplots(1, 2, figsize=(12, 5.2))
a.tripcolor(tri, facecolors=run.level[keep].astype(float), cmap="viridis", edgecolors="k", linewidth=0.05)
a.set_title("aq.mesh: North Atlantic triangles by level")
a.set_xlim(-80, 0); a.set_ylim(0, 70); a.set_aspect(1.4)
a.set_xlabel("longitude"); a.set_ylabel("latitude")
levels = np.where(mask.levels == 255, np.nan, mask.levels)
b.pcolormesh(mask.lon_edges, np.arange(mask.levels.shape[0] + 1), levels, cmap="viridis", shading="flat")
b.set_title("aq.mask: quadtree level per pixel (rotated Mercator lattice)")
b.set_xlabel("longitude (rotated frame)"); b.set_ylabel("lattice row")
fig.tight_layout()
fig.savefig(sys.argv[1] if len(sys.argv) > 1 else "python_mercator.png", dpi=80)
