"""Sweeps over cable-length grids and workspaces on dask.distributed, results in Parquet."""
