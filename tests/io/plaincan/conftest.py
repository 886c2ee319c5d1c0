"""The plain-CAN tests register the beacon (beacon.py) as an installed
package would register a device."""

import pytest

from softplc.runtime.plugin.registry import extended

from .beacon import DEVICE


@pytest.fixture(autouse=True)
def beacon_registered():
    with extended(DEVICE):
        yield
