"""The result codes of a Modbus transaction, as the program reads them
(MODBUS_CHANNEL[i].LastError, MODBUS_REQUEST.ERRORID; the MODBUS_ERR_*
constants of fblocks/comm/modbus.st). Pure data, no pymodbus."""

from __future__ import annotations

import enum


class ModbusError(enum.IntEnum):
    """Result codes of a transaction (channel LastError, MODBUS_REQUEST.ERRORID).
    1..11 are the slave's exception codes (Modbus application protocol 7);
    16#A1.. are the master's own, numbered as CODESYS numbers them."""

    OK = 0x00
    ILLEGAL_FUNCTION = 0x01
    ILLEGAL_DATA_ADDRESS = 0x02
    ILLEGAL_DATA_VALUE = 0x03
    SLAVE_DEVICE_FAILURE = 0x04
    ACKNOWLEDGE = 0x05
    SLAVE_DEVICE_BUSY = 0x06
    MEMORY_PARITY_ERROR = 0x08
    GATEWAY_PATH_UNAVAILABLE = 0x0A
    GATEWAY_TARGET_FAILED = 0x0B
    RESPONSE_CRC_FAIL = 0xA1  # an answer whose CRC does not match (RTU)
    RESPONSE_TIMEOUT = 0xA2  # no answer, retries included: a silent slave
    RESPONSE_WRONG_SLAVE = 0xA3  # another unit answered
    RESPONSE_WRONG_FUNCTIONCODE = 0xA4  # the answer is of another function
    REQUEST_FAILED_TO_SEND = 0xA5  # the connection is down (no port, refused, reset)
    RESPONSE_INVALID_DATA = 0xA6  # an answer that does not fit its request (length, counts, echo)
    RESPONSE_INVALID_PROTOCOL = 0xA7  # TCP: a protocol id other than 0 in the MBAP header
    RESPONSE_INVALID_HEADER = 0xA8  # TCP: a header that does not frame (transaction id, length)
    INVALID_REQUEST = 0xFE  # softplc: a request the master refuses to send (bad count ...)
    UNDEFINED = 0xFF


#: The exception codes Modbus defines (application protocol V1.1b3, 7): an
#: exception answer with any other code (0 included) is not a valid answer.
EXCEPTION_CODES = frozenset(
    {
        ModbusError.ILLEGAL_FUNCTION,
        ModbusError.ILLEGAL_DATA_ADDRESS,
        ModbusError.ILLEGAL_DATA_VALUE,
        ModbusError.SLAVE_DEVICE_FAILURE,
        ModbusError.ACKNOWLEDGE,
        ModbusError.SLAVE_DEVICE_BUSY,
        ModbusError.MEMORY_PARITY_ERROR,
        ModbusError.GATEWAY_PATH_UNAVAILABLE,
        ModbusError.GATEWAY_TARGET_FAILED,
    }
)


def error_text(code: int) -> str:
    try:
        return ModbusError(code).name.lower().replace("_", " ")
    except ValueError:
        return f"error 16#{code:02X}"
