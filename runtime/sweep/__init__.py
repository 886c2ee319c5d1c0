"""Sweeps: many scenarios of one configuration, each a deterministic run in
virtual time, in parallel or on a Dask cluster (`softplc sweep`, and the
pytest parametrisation of softplc.testing).

matrix.py    the sweep file: [matrix], [[scenario]] or [random], and [result]
expr.py      the [result] expressions (values, expectations), never eval()
scenario.py  a scenario's tables and its run (a Job: picklable) into a row
execute.py   where the jobs run: this process, a process pool, a Dask cluster
table.py     the rows as CSV or Parquet, and the plot
"""
