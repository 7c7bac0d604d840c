"""Field conversions shared by the client's command builders."""
import numpy as np


def vector(value, n, field):
    """A length-n list of floats; only the shape is checked (the server validates values)."""
    a = np.asarray(value, dtype=np.float64)
    if a.shape != (n,):
        raise ValueError("%s must have %d components, got shape %s" % (field, n, a.shape))
    return [float(x) for x in a]
