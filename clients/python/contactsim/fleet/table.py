"""Rows of dicts -> a pandas DataFrame with the columns in a fixed order."""
FIRST = ("tag", "method", "params", "steps", "final_step", "state_hash", "max_penetration", "mean_contacts",
         "energy_initial", "energy_final", "energy_drift", "ms_per_step", "worker", "host", "attempts",
         "retried_after", "error")


def rows_frame(rows):
    import pandas as pd
    df = pd.DataFrame([r for r in rows if r is not None])
    first = [c for c in FIRST if c in df.columns]
    df = df[first + [c for c in df.columns if c not in first]]
    return df.drop(columns=[c for c in ("retryable",) if c in df.columns])
