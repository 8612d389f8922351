"""A solver that lives on several GPUs: the points cut into one part per GPU, each part's rows
(its own points', in global ids) left on its GPU. Prints a line and exits 0 where there is no GPU."""
import numpy as np

import horizon

if not horizon.backend_available("cuda"):
    print("no GPU: nothing to show")
else:
    points = horizon.lattice(60)
    h = 1.5 * 10 / 60
    parts = horizon.search(points, h, backend="cuda", devices=[0, 0], keep_on_device=True)  # GPUs 0 and 1 on a 2-GPU machine
    for part in parts:  # part.offsets, part.indices, part.device_ids: CUDA arrays on part.device
        print(f"GPU {part.device}: {len(part)} points + {part.halo} halo, {part.total} entries")
    whole = horizon.search(points, h, backend="serial")
    first = parts[0].to_host()
    assert np.array_equal(first.row(0), whole.row(parts[0].ids[0]))
    assert sum(part.total for part in parts) == whole.total
