"""Traces of `softplc run` for people to look at: the values of the watched
variables over engine time as VCD (GTKWave) and as a plot (PNG, SVG, PDF),
and the reading of CSV and VCD traces back for `softplc plot`.

series.py  Series and Trace (samples per signal), Recorder (an after_tick
           callback that keeps the samples a plot needs), read_csv
vcd.py     VcdTraceWriter (an after_tick callback) and read_vcd
reading.py read_trace: a CSV or a VCD, by its ending
plot.py    plot(): a Trace as a figure (matplotlib, the `plot` extra)
events.py  what the simulated devices recorded (breaker closes, EMCYs), as
           the traces' events and marks

The CSV trace itself is written by engine/monitor.py (TraceWriter; the
events' column given to it by events.csv_column).
"""
