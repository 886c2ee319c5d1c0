"""What CODESYS V3 writes about an SFC beside TC6: the addData of its
steps (``http://www.3s-software.com/plcopenxml/sfc/element``: attributes
keyed by GUID) and of its POU (``.../sfcsettings``).

A step's attributes name its step action (run while the step is active),
its entry action and its exit action; they become the IEC ed.3
associations N, P1 and P0, the last two through an action of their own
that calls the entry or exit action only while its Q is TRUE: an IEC P1
or P0 action runs twice (its pulse and its final scan), CODESYS runs an
entry or exit action once. Its minimum and maximum time are not
supervised here (W210), and the SFC flags a POU declares for use
(SFCInit, SFCReset, SFCPause ...) are not driven (W212).
"""

from __future__ import annotations

from .bodies import BodyOut
from .xmlsafe import PosElement

_ELEMENT = "http://www.3s-software.com/plcopenxml/sfc/element"
_SETTINGS = "http://www.3s-software.com/plcopenxml/sfcsettings"
_MAIN = "700a583f-b4d4-43e4-8c14-629c7cd3bec8"
_ENTRY = "a6b08bd8-b696-47e3-9cbf-7408b61c9ff8"
_EXIT = "a2621e18-7de3-4ea6-ae6d-89e9e0b7befd"
_DUPLICATE = "62e1754b-7629-4e63-9cec-10ae0c536f1f"
_MIN_TIME = "cacf1a68-236e-47c2-b7b1-1cf9199718cb"
_MAX_TIME = "b693554c-1b01-4a8d-afde-9e3a46f7465d"


def _attributes(el: PosElement) -> dict:
    """guid -> <attribute> element, of el's CODESYS sfc/element addData."""
    found = {}
    add = el.kid("addData")
    for data in add.kids("data") if add is not None else []:
        if data.get("name") == _ELEMENT:
            for attr in data.walk("attribute"):
                found[attr.get("guid", "").strip("{}").lower()] = attr
    return found


def codesys_step(step: PosElement, out: BodyOut) -> tuple:
    """(duplicated, [(action, qualifier, element, once)]) of a step: whether
    CODESYS marks it as another drawing of a step of the same name, and
    the associations its step, entry and exit actions make (once: "entry"
    or "exit" for an action CODESYS runs once, else None)."""
    attrs = _attributes(step)
    assocs = []
    for guid, qualifier, what in ((_ENTRY, "P1", "entry"), (_MAIN, "N", "step"), (_EXIT, "P0", "exit")):
        attr = attrs.get(guid)
        name = (attr.text or "").strip() if attr is not None else ""
        if attr is None or not name:
            continue
        if not (name.isascii() and name.replace("_", "a").isalnum() and not name[0].isdigit()):
            out.error("E183", f"the {what} action {name!r} is not an ST identifier", attr)
            continue
        assocs.append((name, qualifier, attr, what if qualifier != "N" else None))
    for guid, what in ((_MIN_TIME, "minimum"), (_MAX_TIME, "maximum")):
        attr = attrs.get(guid)
        value = (attr.text or "").strip() if attr is not None else ""
        if attr is not None and any(c in "123456789" for c in value):
            out.warning(
                "W210",
                f"step {step.get('name')}: its {what} time {value} is not supervised",
                attr,
                f"test the step's time in a transition or an action, e.g. {step.get('name')}.T > {value}",
            )
    dup = attrs.get(_DUPLICATE)
    return dup is not None and (dup.text or "").strip().upper() == "TRUE", assocs


def sfc_settings(owner: PosElement | None, out: BodyOut) -> None:
    """W212 for each SFC flag the POU's settings say it uses."""
    add = owner.kid("addData") if owner is not None else None
    for data in add.kids("data") if add is not None else []:
        if data.get("name") != _SETTINGS:
            continue
        for flags in data.walk("Flags"):
            for flag in flags.kids():
                if flag.get("Use", "").lower() == "true":
                    out.warning(
                        "W212",
                        f"the SFC flag SFC{flag.name} is used in CODESYS: softplc neither drives nor reads it",
                        flag,
                        "the chart runs without it; read the steps' X and T instead (Step3.X, Step3.T)",
                    )
