"""The loopback driver alone (no engine): what a program writes to %Q at
the end of cycle n is in %I at the start of cycle n+1."""

from __future__ import annotations

import pytest

from softplc.runtime.image.address import parse_address
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.io.loopback.driver import LoopbackDriver
from softplc.runtime.plugin.driver import Driver, DriverError
from softplc.runtime.program import ExecContext, compile_files


def scan(driver, image, program_step, cycles):
    """The engine's order, by hand: read inputs, run, write outputs."""
    for _ in range(cycles):
        driver.read_inputs(image)
        program_step()
        driver.write_outputs(image)


def test_one_cycle_latency():
    drv = LoopbackDriver("loopback[0]", [("%QW0", "%IW10", 2)])
    image = ProcessImage("iec")
    drv.start()
    seen = []
    for n in range(5):
        drv.read_inputs(image)
        seen.append(image.read("%IW10"))
        image.write("%QW0", 100 + n)  # "the program"
        drv.write_outputs(image)
    assert seen == [0, 100, 101, 102, 103]
    assert drv.exchanges == 5


def test_zeros_before_the_first_exchange_and_after_a_restart():
    drv = LoopbackDriver("lb", [("%QB0", "%IB0", 4)])
    image = ProcessImage("iec")
    image.areas["Q"][0:4] = b"\x01\x02\x03\x04"
    image.areas["I"][0:5] = b"\xff\xff\xff\xff\xff"  # stale inputs
    drv.start()
    drv.read_inputs(image)
    assert image.areas["I"][0:5] == b"\0\0\0\0\xff"  # only the linked bytes are written
    drv.write_outputs(image)
    drv.read_inputs(image)
    assert image.areas["I"][0:4] == b"\x01\x02\x03\x04"
    drv.start()  # a restarted bus has sent nothing yet
    drv.read_inputs(image)
    assert image.areas["I"][0:4] == b"\0\0\0\0" and drv.exchanges == 0


def test_several_links_and_a_byte_count_beyond_the_address():
    drv = LoopbackDriver("lb", [("%QW0", "%IW10", None), ("%QB4", "%IB24", 4), ("%QD2", "%ID8", 4)])
    image = ProcessImage("iec")
    image.write("%QW0", 0x1234)
    image.write("%QD1", 0x0D0C0B0A)  # bytes 4-7, the second link's 4 bytes
    image.write("%QD2", 0xCAFE)
    drv.write_outputs(image)
    drv.read_inputs(image)
    assert image.read("%IW10") == 0x1234
    assert image.areas["I"][24:28] == b"\x0a\x0b\x0c\x0d"
    assert image.read("%ID8") == 0xCAFE
    st = drv.status()
    assert st.ok and st.message == "10 bytes looped in 3 links, 1 exchanges"
    assert [str(link) for link in drv.links] == [
        "%QW0 -> %IW10, 2 bytes",
        "%QB4 -> %IB24, 4 bytes",
        "%QD2 -> %ID8, 4 bytes",
    ]


def test_the_safe_output_view_is_what_gets_looped():
    drv = LoopbackDriver("lb", [("%QW1", "%IW1", 2)])
    image = ProcessImage("iec")
    image.write("%QW1", 999)  # what the (faulted) program left in %Q
    safe = ProcessImage("iec")  # the engine builds its safe %Q area like this
    safe.write("%QW1", 1234)
    drv.write_outputs(image.outputs_view(safe.areas["Q"]))
    drv.read_inputs(image)
    assert image.read("%IW1") == 1234 and image.read("%QW1") == 999


def test_schneider_words():
    # word indices: %QW10 is bytes 20-21, %IW20 bytes 40-41; a :n table is n words
    drv = LoopbackDriver("lb", [("%QW10:3", "%IW20:3", None), ("%QD40", "%ID50", None)], addressing="schneider")
    image = ProcessImage("schneider")
    image.write("%QW10:3", [1, 2, 3])
    image.write("%QD40", 0x00032007)
    drv.write_outputs(image)
    drv.read_inputs(image)
    assert image.read("%IW20:3") == [1, 2, 3] and image.areas["I"][40:46] == b"\1\0\2\0\3\0"
    assert (image.read("%IW50"), image.read("%IW51")) == (0x2007, 0x0003)
    assert drv.status().message.startswith("10 bytes looped in 2 links")


def test_a_compiled_program_counts_through_the_loop():
    # %QW0 := %IW0 + 1 through the loopback: one step per cycle, exactly.
    prog = compile_files(
        [],
        profile="codesys",
        texts={
            "count.st": """
PROGRAM count
VAR n_in AT %IW0 : INT; n_out AT %QW0 : INT; END_VAR
n_out := n_in + 1;
END_PROGRAM
"""
        },
    )
    image = ProcessImage("iec")
    runner = prog.runner("count", ctx=ExecContext(image))
    drv = LoopbackDriver("lb", [(parse_address("%QW0"), parse_address("%IW0"), 2)])
    assert isinstance(drv, Driver)
    drv.start()
    scan(drv, image, lambda: runner.run(1), 25)
    assert image.read("%QW0") == 25 and image.read("%IW0") == 24
    drv.stop()


@pytest.mark.parametrize(
    "links, message",
    [
        ([("%QW0", "%QW10", 2)], "lb: link 0 (%QW0 -> %QW10): a link copies %Q outputs to %I inputs, not %Q to %Q"),
        ([("%IW0", "%IW10", 2)], "not %I to %I"),
        (
            [("%QW0", "%IW0", 2), ("%QX0.1", "%IB4", 1)],
            "lb: link 1 (%QX0.1 -> %IB4): %QX0.1 is a bit; drivers copy whole bytes",
        ),
        (
            [("%QW0", "%IW0", 2), ("%QW1", "%IW2", 2), ("%QB9", "%IB1", 1)],
            "lb: link 2 (%QB9 -> %IB1, 1 byte) writes inputs that link 0 (%QW0 -> %IW0, 2 bytes) already writes",
        ),
        ([("%QW0", "%IW32768", 2)], "lb: link 0 (%QW0 -> %IW32768): %IW32768 (bytes 65536..65537) is outside"),
        (
            [("%QB65535", "%IB0", 2)],
            "lb: link 0 (%QB65535 -> %IB0): 2 bytes from byte 65535 run past the end of the 65536-byte %Q area",
        ),
        ([("%QW0", "%IW0", 0)], "lb: link 0 (%QW0 -> %IW0): nbytes must be a positive integer, not 0"),
        ([("%QW0", "%IW0", "2")], "nbytes must be a positive integer, not '2'"),
        ([("%QZ0", "%IW0", 2)], "lb: link 0 (%QZ0 -> %IW0): '%QZ0' is not a direct address"),
        ([("%QW0",)], "lb: link 0 must be (source, target, nbytes), not ('%QW0',)"),
        ([("%QW0:2", "%IW0", 4)], "lb: link 0 (%QW0:2 -> %IW0): %QW0:2 is Schneider addressing"),
    ],
)
def test_bad_links_are_refused_before_the_first_cycle(links, message):
    with pytest.raises(DriverError) as exc:
        LoopbackDriver("lb", links)
    assert message in str(exc.value)


def test_an_image_of_another_layout_is_refused():
    drv = LoopbackDriver("lb", [("%QW0", "%IW0", 2)], addressing="schneider")
    with pytest.raises(
        DriverError, match="lb: configured for a 65536-byte schneider image, given a 65536-byte iec one"
    ):
        drv.read_inputs(ProcessImage("iec"))


def test_an_unknown_addressing_model_is_a_driver_error():
    with pytest.raises(DriverError, match="lb: unknown addressing model 'unity'"):
        LoopbackDriver("lb", [], addressing="unity")
