"""Sweeps: many runs at once over a grid of parameters and starts, from a signed numeric record, in
chunks, with tables written as CSV or Parquet (Dask optional)."""
