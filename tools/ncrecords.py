"""Finding one output time in a swe-mps netCDF file (shared by the plotting scripts)."""
import numpy as np


def record(ds, time):
    """Index k of the output time nearest `time` (the last one if None), and the slice of
    the contiguous ragged particle arrays that belongs to it."""
    times = ds["time"][:]
    k = int(np.argmin(np.abs(times - time))) if time is not None else len(times) - 1
    counts = ds["particle_count"][:].astype(np.int64)
    start = int(counts[:k].sum())
    return k, slice(start, start + int(counts[k]))
