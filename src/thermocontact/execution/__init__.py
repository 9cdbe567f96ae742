"""Running many independent tasks: in this process, a process pool or a Dask cluster."""
