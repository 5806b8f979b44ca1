"""What bad arguments are told: a count or seed out of range names the argument and the
range, numbers as strings are read as the command line reads them, a table of inputs held
in memory is named as such (never by the temporary file it was written to), a key left out
says what holds in its place."""

import numpy as np
import polars as pl
import pytest

import touchdown

MAX = "9223372036854775807 (2^63 - 1)"


@pytest.mark.parametrize(
    "call, said",
    [
        (lambda: touchdown.sweep(samples=-5), f"samples=-5 is out of range: expected a whole number from 1 to {MAX}"),
        (lambda: touchdown.sweep(samples=2**64), f"samples=18446744073709551616 is out of range: expected a whole number from 1 to {MAX}"),
        (lambda: touchdown.sweep(samples=np.int64(-3)), "samples=np.int64(-3) is out of range: expected a whole number from 1 to"),
        (lambda: touchdown.sweep(samples=1e300), "samples=1e+300 is out of range: expected a whole number from 1 to"),
        (lambda: touchdown.sweep(seed=-1), f"seed=-1 is out of range: expected a whole number from 0 to {MAX}"),
        (lambda: touchdown.sweep(threads=0), "threads=0 is out of range: expected a whole number from 1 to 1024"),
        (lambda: touchdown.sweep(threads=5000), "threads=5000 is out of range: expected a whole number from 1 to 1024"),
        (lambda: touchdown.trace(sample=-1), f"sample=-1 is out of range: expected a whole number from 0 to {MAX}"),
        (lambda: touchdown.trace(sample=3, seed=-2), "seed=-2 is out of range: expected a whole number from 0 to"),
        (lambda: touchdown.trace(sample=3, every=0), f"every=0 is out of range: expected a whole number from 1 to {MAX}"),
    ],
)
def test_a_count_out_of_range_names_the_argument_and_the_range(call, said):
    # A ValueError (not the OverflowError of a conversion to an unsigned number).
    with pytest.raises(ValueError) as raised:
        call()
    assert str(raised.value).startswith(said), str(raised.value)


def test_numbers_as_strings_are_read_as_the_command_line_reads_them():
    # "1e2" as `--samples 1e2`, "2_0" as `--seed 2_0`: the command line's own parser.
    assert touchdown.sweep(samples="1e2", seed="2_0", progress=False).equals(
        touchdown.sweep(samples=100, seed=20, progress=False)
    )
    assert touchdown.sweep(samples="2.5e1", progress=False).num_rows == 25
    assert touchdown.trace(sample="3", seed="9", every="1e1").table.equals(
        touchdown.trace(sample=3, seed=9, every=10).table
    )
    with pytest.raises(ValueError, match=r'^samples: "many" is not a whole number \(examples: 250000, 1e6, 2.5e5\); expected a whole number from 1 to'):
        touchdown.sweep(samples="many", progress=False)
    with pytest.raises(ValueError, match=r"^samples: \"1.5\" is not a whole number"):
        touchdown.sweep(samples="1.5", progress=False)
    with pytest.raises(ValueError, match=r"^samples='-5' is out of range: expected a whole number from 1 to"):
        touchdown.sweep(samples="-5", progress=False)
    with pytest.raises(ValueError, match=r"^threads='2000' is out of range: expected a whole number from 1 to 1024"):
        touchdown.sweep(samples=10, threads="2000", progress=False)


def test_what_is_not_a_number_is_named():
    with pytest.raises(TypeError, match=r"^samples=\[10\]: expected a whole number from 1 to .*, not a list"):
        touchdown.sweep(samples=[10], progress=False)
    with pytest.raises(TypeError, match=r"^sample=None: expected a whole number from 0 to .*, not a NoneType"):
        touchdown.trace(sample=None)
    with pytest.raises(TypeError, match=r"^seed=True: expected a whole number from 0 to .*, not a bool"):
        touchdown.sweep(samples=10, seed=True, progress=False)


def test_a_table_of_inputs_in_memory_is_named_as_the_table_given():
    frame = pl.DataFrame({"slope": [1.0, 2.0]})
    with pytest.raises(touchdown.TouchdownError) as raised:
        touchdown.sweep(inputs=frame, progress=False)
    said = str(raised.value)
    assert said.startswith("inputs (the table given): unknown column slope"), said
    assert "touchdown-inputs-" not in said and "inputs.arrow" not in said, said


def test_a_trace_of_a_sweep_of_a_table_in_memory_asks_for_the_table():
    frame = pl.DataFrame({"slope_deg": [1.0, 2.0, 3.0]})
    table = touchdown.sweep(inputs=frame, progress=False)
    # The table's temporary file went with the sweep: the message asks for the table.
    with pytest.raises(touchdown.TouchdownError) as raised:
        touchdown.trace(table, sample=1)
    said = str(raised.value)
    assert said.startswith(
        "the sweep table ran a table of inputs held in memory: give trace inputs= that table again"
    ), said
    assert "touchdown-inputs-" not in said, said
    # Another table in its place is named as the table given.
    with pytest.raises(touchdown.TouchdownError) as raised:
        touchdown.trace(table, sample=1, inputs=pl.DataFrame({"slope_deg": [9.0, 9.0, 9.0]}))
    said = str(raised.value)
    assert said.startswith("inputs (the table given) is not the table of inputs the sweep table ran"), said
    assert "touchdown-inputs-" not in said, said
    # The same table again traces its row.
    assert touchdown.trace(table, sample=1, inputs=frame).outcome == table.column("outcome")[1].as_py()


def test_a_key_left_out_says_what_holds():
    s = touchdown.Scenario.from_toml("")
    with pytest.raises(KeyError, match=r"does not give `surface.friction_coefficient`: its default holds, surface.friction_coefficient = 0.6"):
        s["surface.friction_coefficient"]
    with pytest.raises(KeyError, match=r"does not give `limits.axial_force_n`, which has no default: no such limit applies"):
        s["limits.axial_force_n"]
    # A key the scenario does not know is told so, with the closest known key.
    with pytest.raises(KeyError, match=r"scenario key `limits.axial_forc` is unknown \(did you mean `axial_force_n`\?\)"):
        s["limits.axial_forc"]
    with pytest.raises(KeyError, match=r"its default holds, surface.friction_coefficient = 0.6"):
        del s["surface.friction_coefficient"]
