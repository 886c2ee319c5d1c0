"""The retain file: written whole or not at all (a real process killed
with SIGKILL while it writes), read back exactly, a damaged one refused and
set aside, a file softplc did not write never touched
(runtime/engine/retain_file.py)."""

from __future__ import annotations

import hashlib
import json
import math
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest

from softplc.runtime.engine.retain import RetainData
from softplc.runtime.engine.retain_file import ForeignRetainFile, RetainFileError, RetainStore, read_file, write_file

from .retain_child import block as child_block

CHILD = Path(__file__).with_name("retain_child.py")


def small_data(counter: int = 1) -> RetainData:
    return RetainData(
        "layout-1",
        123,
        counter,
        {
            "Main.count": {"kind": "RETAIN", "type": "DINT", "value": counter},
            "Main.r": {"kind": "RETAIN", "type": "LREAL", "value": float("nan")},
            "Main.big": {"kind": "PERSISTENT", "type": "ULINT", "value": (1 << 64) - 1},
        },
    )


def test_file_round_trip_is_exact_and_readable(tmp_path):
    path = tmp_path / "plc.retain"
    write_file(path, small_data(5))
    back = read_file(path)
    assert back.layout == "layout-1" and back.saved_ns == 123 and back.cycle == 5
    assert back.vars["Main.big"]["value"] == (1 << 64) - 1 and math.isnan(back.vars["Main.r"]["value"])
    header, body = path.read_bytes().split(b"\n", 1)
    assert json.loads(header)["format"] == "softplc-retain"
    assert b'"Main.count": {"kind": "RETAIN", "type": "DINT", "value": 5}' in body  # one variable a line
    assert read_file(tmp_path / "missing.retain") is None
    assert sorted(os.listdir(tmp_path)) == ["plc.retain"]  # no temporary file left


def _flip(raw: bytes) -> bytes:
    i = len(raw) - 20
    return raw[:i] + bytes([raw[i] ^ 0x01]) + raw[i + 1 :]


def _version2(raw: bytes) -> bytes:
    head, body = raw.split(b"\n", 1)
    h = json.loads(head)
    h["version"] = 2
    return json.dumps(h).encode() + b"\n" + body


@pytest.mark.parametrize(
    "damage, message",
    [
        (_flip, "bad checksum"),
        (lambda raw: raw[: len(raw) // 2], "truncated"),
        (lambda raw: raw.split(b"\n", 1)[0] + b"\n", "truncated (0 of"),
        (lambda raw: raw + b"\n", "trailing data"),
        (_version2, "version 2 is not known"),
    ],
    ids=["flipped-byte", "truncated", "no-body", "trailing", "version"],
)
def test_damaged_file_is_refused_and_kept_aside(tmp_path, damage, message):
    path = tmp_path / "plc.retain"
    write_file(path, small_data())
    bad = damage(path.read_bytes())
    path.write_bytes(bad)
    with pytest.raises(RetainFileError) as err:
        read_file(path)
    assert str(path) in str(err.value) and message in str(err.value)
    assert "Traceback" not in str(err.value)

    data, warning = RetainStore(path, threaded=False).load()
    assert data is None
    corrupt = tmp_path / "plc.retain.corrupt"
    assert message in warning and str(corrupt) in warning and "initial values" in warning
    assert corrupt.read_bytes() == bad and not path.exists()


@pytest.mark.parametrize(
    ("content", "message"),
    [
        (b"\x00\xffGIF89a garbage" * 50, "not a softplc retain file"),
        (b'{"layout": "x", "saved_ns": 0, "cycle": 0, "vars": {}}\n', "not a softplc retain file"),
        (b"my notes, not a retain file\n", "not a softplc retain file"),
    ],
    ids=["garbage", "no-header", "someone's file"],
)
def test_a_file_softplc_did_not_write_is_neither_renamed_nor_written_over(tmp_path, content, message):
    """Only a file with softplc's header is softplc's to set aside; anything
    else at the retain path stops the start (a save would write over it)."""
    path = tmp_path / "plc.retain"
    path.write_bytes(content)
    store = RetainStore(path, threaded=False)
    with pytest.raises(ForeignRetainFile) as err:
        store.load()
    assert str(err.value) == (
        f"{path}: {message} (no 'softplc-retain' header on line 1): softplc would write over it; "
        "move it away or name another file in [retain] file"
    )
    assert os.listdir(tmp_path) == ["plc.retain"] and path.read_bytes() == content


def test_an_empty_file_is_written_over_not_set_aside(tmp_path):
    """Nothing to lose: the first save writes it (it was renamed .corrupt)."""
    path = tmp_path / "plc.retain"
    path.write_bytes(b"")
    store = RetainStore(path, threaded=False)
    assert store.load() == (None, f"{path}: the retain file is empty; starting with initial values")
    assert os.listdir(tmp_path) == ["plc.retain"]
    store.submit(small_data(4))
    assert read_file(path).cycle == 4


@pytest.mark.parametrize("kind", ["fifo", "directory", "link", "device"])
def test_what_is_no_regular_file_is_never_read_renamed_or_written(tmp_path, kind):
    """[retain] file = "/dev/null", run as root, renamed /dev/null to
    /dev/null.corrupt (an empty "file" was taken for a damaged one)."""
    path = tmp_path / "plc.retain"
    if kind == "fifo":
        os.mkfifo(path)  # reading it would block for ever
        what = "a FIFO"
    elif kind == "directory":
        path.mkdir()
        what = "a directory"
    elif kind == "link":
        write_file(tmp_path / "elsewhere.retain", small_data(1))
        path.symlink_to(tmp_path / "elsewhere.retain")  # the rename would replace the link
        what = "a symbolic link"
    else:
        if os.geteuid() != 0:
            pytest.skip("creating a device node needs root")
        os.mknod(path, 0o666 | stat.S_IFCHR, os.makedev(1, 3))  # /dev/null's numbers, here
        what = "a character device"
    before = os.lstat(path)
    store = RetainStore(path, threaded=False)
    with pytest.raises(ForeignRetainFile) as err:
        store.load()
    assert str(err.value).startswith(f"{path}: {what}, not a retain file")
    store.submit(small_data(2))  # a save does not rename over it either
    assert store.last_error == (
        f"{path}: cannot write the retain file: {what} is there, not a retain file; softplc writes over none"
    )
    after = os.lstat(path)
    assert (after.st_ino, after.st_mode) == (before.st_ino, before.st_mode)
    assert sorted(os.listdir(tmp_path)) == sorted(["plc.retain"] + (["elsewhere.retain"] if kind == "link" else []))


def test_checksum_valid_but_malformed_body(tmp_path):
    path = tmp_path / "plc.retain"
    body = b'{"layout": 1, "vars": []}'
    head = json.dumps(
        {"format": "softplc-retain", "version": 1, "sha256": hashlib.sha256(body).hexdigest(), "length": len(body)}
    )
    path.write_bytes(head.encode() + b"\n" + body)
    with pytest.raises(RetainFileError, match="malformed retain file"):
        read_file(path)


def test_load_removes_temp_files_and_keeps_earlier_corrupt_files(tmp_path):
    path = tmp_path / "plc.retain"
    (tmp_path / ".plc.retain.4242.deadbeef.tmp").write_bytes(b"half a retain fi")
    (tmp_path / "other.tmp").write_bytes(b"not ours")
    (tmp_path / "plc.retain.corrupt").write_bytes(b"an older one")
    write_file(path, small_data(2))
    path.write_bytes(path.read_bytes()[:-5])  # softplc's, truncated
    data, warning = RetainStore(path, threaded=False).load()
    assert data is None and "plc.retain.corrupt.2" in warning
    assert sorted(os.listdir(tmp_path)) == ["other.tmp", "plc.retain.corrupt", "plc.retain.corrupt.2"]
    write_file(path, small_data(3))
    assert RetainStore(path, threaded=False).load() == (read_file(path), None)


@pytest.mark.realtime  # kills a writer at real moments
def test_file_stays_whole_when_the_writer_is_killed(tmp_path):
    """A real process writes the file in a tight loop and is killed with
    SIGKILL at varied moments; the file always reads back whole, with its
    checksum, and never goes back to an older counter."""
    if not hasattr(signal, "SIGKILL") or not hasattr(os, "fork"):
        pytest.skip("needs SIGKILL and fork")
    path = tmp_path / "plc.retain"
    child = subprocess.Popen(
        [sys.executable, str(CHILD), str(path)],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    writer = None
    prev = -1
    try:
        for i in range(20):
            child.stdin.write(f"{prev + 1}\n")
            child.stdin.flush()
            line = child.stdout.readline()
            if not line.strip().isdigit():
                pytest.fail(f"the child did not start a writer: {line!r} {child.stderr.read()}")
            writer = int(line)
            deadline = time.monotonic() + 20
            while True:  # until the writer has replaced the file at least once
                data = read_file(path)
                if data is not None and data.cycle > prev:
                    break
                if child.poll() is not None:
                    pytest.fail(f"the child died: {child.stderr.read()}")
                assert time.monotonic() < deadline, "the writer wrote nothing"
                time.sleep(0.0005)
            time.sleep((i % 5) * 0.0013)  # varies where the kill lands, nothing else
            os.kill(writer, signal.SIGKILL)
            assert child.stdout.readline() == "reaped\n", child.stderr.read()
            writer = None
            data = read_file(path)  # raises on a damaged file
            counter = data.vars["Main.counter"]["value"]
            assert counter > prev and data.cycle == counter
            assert data.vars["Main.block"]["value"] == child_block(counter)
            prev = counter
    finally:  # no writer may outlive the test
        if writer is not None:
            try:
                os.kill(writer, signal.SIGKILL)
            except ProcessLookupError:
                pass
        child.stdin.close()
        try:
            child.wait(timeout=10)
        except subprocess.TimeoutExpired:
            child.kill()
            child.wait()
        child.stdout.close()
        child.stderr.close()
    assert child.returncode == 0
    loaded, warning = RetainStore(path, threaded=False).load()
    assert warning is None and loaded.cycle == prev
    assert os.listdir(tmp_path) == ["plc.retain"]  # a killed write's temporary file is gone


# ================================================================ the store


def test_store_writes_the_newest_snapshot_in_the_background(tmp_path):
    path = tmp_path / "plc.retain"
    store = RetainStore(path)
    for k in range(300):
        store.submit(small_data(k))
    assert store.flush()
    assert read_file(path).cycle == 299
    assert 1 <= store.writes <= 300 and store.last_error is None
    store.submit(small_data(300))
    store.close()
    assert read_file(path).cycle == 300
    store.submit(small_data(301))  # after close: written at once, not lost
    assert read_file(path).cycle == 301


def test_store_reports_a_failed_write_and_retries(tmp_path):
    path = tmp_path / "not-yet" / "plc.retain"
    for threaded in (True, False):
        store = RetainStore(path, threaded=threaded)
        store.submit(small_data(1))  # must not raise
        assert store.flush(timeout=5) is False
        assert store.last_error is not None and str(path) in store.last_error
        assert "No such file" in store.last_error
        assert store.errors >= 1 and store.writes == 0
        store.close()
    path.parent.mkdir()
    store = RetainStore(path)
    store.submit(small_data(1))
    store.flush()
    path.unlink()
    path.parent.rmdir()
    store.submit(small_data(2))
    assert store.flush(timeout=5) is False and store.last_error
    path.parent.mkdir()
    assert store.flush() is True  # the failed snapshot is tried again
    assert store.last_error is None and read_file(path).cycle == 2
    store.submit(small_data(3))
    store.close()
    assert read_file(path).cycle == 3
