"""The log of the web page: a logging.Handler on the "softplc" logger that
keeps the last records (KEEP) for the page, each with a sequence number so
that a client gets each record once.

    buffer = LogBuffer()
    buffer.attach()                 # on logging.getLogger("softplc")
    records, last = buffer.since(0) # every record kept, and the last number
    records, last = buffer.since(last)
    buffer.detach()
"""

from __future__ import annotations

import collections
import logging

#: how many records the page can scroll back through
KEEP = 500


class LogBuffer(logging.Handler):
    def __init__(self, keep: int = KEEP, logger: str = "softplc") -> None:
        super().__init__(logging.NOTSET)
        self.records: collections.deque = collections.deque(maxlen=keep)
        self.sequence = 0
        self.logger = logging.getLogger(logger)

    def attach(self) -> None:
        self.logger.addHandler(self)

    def detach(self) -> None:
        self.logger.removeHandler(self)

    def emit(self, record: logging.LogRecord) -> None:
        try:
            message = record.getMessage()
            if record.exc_info and record.exc_info[1] is not None:
                message += f" ({record.exc_info[1]!r})"
        except Exception:  # a bad format string in someone's log call: say so, never raise here
            message = f"{record.msg!r} (unformattable: {record.args!r})"
        # emit() runs under the handler's lock (Handler.handle), as since() does
        self.sequence += 1
        self.records.append(
            {
                "seq": self.sequence,
                "time": record.created,
                "level": record.levelname,
                "name": record.name,
                "message": message,
            }
        )

    def extend(self, records: list) -> None:
        """Records kept by another buffer (the PLC's, sent to the servers'
        process with the snapshots), with their numbers."""
        self.acquire()
        try:
            self.records.extend(records)
            self.sequence = max(self.sequence, records[-1]["seq"])
        finally:
            self.release()

    def since(self, sequence: int) -> tuple:
        """The records after number sequence (those still kept), and the last number."""
        self.acquire()
        try:
            last = self.sequence
            if sequence >= last:
                return [], last
            return [r for r in self.records if r["seq"] > sequence], last
        finally:
            self.release()
