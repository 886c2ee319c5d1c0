"""The PLC configuration: a declarative TOML file, validated and turned into
the plain dataclasses the engine uses.

    cfg = load_config("io_config/plant.toml")     # PlcConfig, or ConfigError

The file::

    [plc]          profile, programs (ST files), on_fault, start
    [retain]       file, period                              (optional)
    [[task]]       name, interval | freewheeling (+ pause), priority,
                   watchdog, sensitivity, programs           (zero or more)
    [outputs]      safe = { "%QX0.0" = false, ... }          (optional)
    [[sim]]        type, name and the keys of the device's bus and its own
    ... and one section per registered bus ([[loopback]], [[can]],
    [canopen], [[modbus]]: runtime/io/<bus>/config.py)

Every message names the file, the key path and what was expected::

    io_config/plant.toml: task[1].interval: expected a duration such as 10ms, 1s, T#250ms (got '10 parsecs')

Modules: load (reading, the two passes, PlcConfig), plc (the core
sections), sims ([[sim]]), section (what a bus's section provides),
relations (pass 2), values (single values), errors (ConfigError, messages).
"""

from .errors import ConfigError
from .load import PlcConfig, config_from_dict, default_config_path, load_config
from .plc import (
    DEFAULT_PAUSE_NS,
    DEFAULT_RETAIN_PERIOD_NS,
    DEFAULT_SPIN_NS,
    PRIORITY_MAX,
    ProgramInstance,
    RetainConfig,
    SafeOutput,
    TaskConfig,
    default_watchdog_ns,
)
from .section import Attachment, Section, SimOptions
from .sims import SimConfig

__all__ = [
    "DEFAULT_PAUSE_NS",
    "DEFAULT_RETAIN_PERIOD_NS",
    "DEFAULT_SPIN_NS",
    "PRIORITY_MAX",
    "Attachment",
    "ConfigError",
    "PlcConfig",
    "ProgramInstance",
    "RetainConfig",
    "SafeOutput",
    "Section",
    "SimConfig",
    "SimOptions",
    "TaskConfig",
    "config_from_dict",
    "default_config_path",
    "default_watchdog_ns",
    "load_config",
]
