"""[canopen] values the check once crashed on (runtime/io/canopen/config.py):
what pass 2 met with keys the file does not give, and paths the system
cannot use."""

from __future__ import annotations

from ...config.support import error, plant


def test_a_heartbeat_timeout_for_a_guarded_node(tmp_path):
    """The node gives no heartbeat (a guarded node sends none): a KeyError
    on 'heartbeat' took softplc down (exit 4)."""
    assert error(tmp_path, plant("", 'guard_time = "100ms"\nheartbeat_timeout = "300ms"\n')) == (
        "canopen.node[0].heartbeat_timeout",
        "only meaningful with a heartbeat (this node sends none, it is guarded by guard_time)",
    )


def test_an_eds_path_too_long(tmp_path):
    name = "e" * 300 + ".eds"
    key, message = error(tmp_path, plant("", "").replace('eds = "ltmr"', f'eds = "{name}"'))
    assert key == "canopen.node[0].eds"
    assert message == f"file name too long: {str(tmp_path / name)[:60]}… ({len(str(tmp_path / name))} characters)"
