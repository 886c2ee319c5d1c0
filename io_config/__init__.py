# Makes io_config a regular package (softplc.io_config) so that importlib.resources
# finds default.toml in an editable install too.
