"""The Modbus function codes the master speaks and how much each carries.
Pure data, no pymodbus: the configuration checks channels against it, the
link and MODBUS_EXCHANGE check requests with it."""

from __future__ import annotations

# Function codes the master speaks: code -> (reads, writes, bits)
FUNCTIONS = {
    1: (True, False, True),  # Read Coils
    2: (True, False, True),  # Read Discrete Inputs
    3: (True, False, False),  # Read Holding Registers
    4: (True, False, False),  # Read Input Registers
    5: (False, True, True),  # Write Single Coil
    6: (False, True, False),  # Write Single Register
    15: (False, True, True),  # Write Multiple Coils
    16: (False, True, False),  # Write Multiple Registers
    23: (True, True, False),  # Read/Write Multiple Registers
}
# The most one request may carry (Modbus application protocol 6.1-6.17)
READ_LIMIT = {1: 2000, 2: 2000, 3: 125, 4: 125, 23: 125}
WRITE_LIMIT = {5: 1, 6: 1, 15: 1968, 16: 123, 23: 121}


def check_request(function: int, count: int, write_count: int) -> str | None:
    """Why a request cannot be sent, or None."""
    if function not in FUNCTIONS:
        return f"function code {function} is not one of {', '.join(map(str, FUNCTIONS))}"
    reads, writes, _bits = FUNCTIONS[function]
    if reads and not 1 <= count <= READ_LIMIT[function]:
        return f"function {function} reads 1..{READ_LIMIT[function]} items, not {count}"
    if writes and not 1 <= write_count <= WRITE_LIMIT[function]:
        return f"function {function} writes 1..{WRITE_LIMIT[function]} items, not {write_count}"
    return None
