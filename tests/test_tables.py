"""Table 4.1 as the package builds it: each computed value beside the text's, and a note naming
the ledger rows that do not reproduce the text."""

from harp_analysis.reporting import tables


def test_table_4_1_notes_the_rows_that_differ_from_the_text():
    table = tables.table_4_1(("HP", "LP"))
    assert list(table.index) == ["HP", "LP"]
    assert {"drag/weight at launch (text)", "drag/weight at launch", "MKS beta"} <= set(table)
    assert [f"altitude where drag = {n:g} weight, km" for n in (0.001, 0.01)] == [
        column for column in table if "drag = 0.0" in column
    ]
    # LP's drag/weight at launch does not reproduce (its diameter); every printed "drag =
    # weight" altitude is where drag falls to a thousandth of the weight (Table 4.1's caption)
    assert "\u2020 table4.1.n0.lp (does not reproduce)" in table.note["LP"]
    for name in ("HP", "LP"):
        assert "the text's altitude is where drag = 0.001 weight" in table.note[name]
