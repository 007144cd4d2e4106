"""The chapters' Russian text (aerophoto.i18n.prose): blocks keyed by cell id and the English text's hash."""

import json

from aerophoto.i18n import prose


def _nb(tmp_path, cells):
    nb = {"nbformat": 4, "nbformat_minor": 5, "metadata": {}, "cells": cells}
    p = tmp_path / "03_demo.ipynb"
    p.write_text(json.dumps(nb), encoding="utf-8")
    return p, nb


def _md(cid, text):
    return {"cell_type": "markdown", "id": cid, "metadata": {}, "source": text}


def _code(cid, text):
    return {"cell_type": "code", "id": cid, "metadata": {}, "source": text, "outputs": [], "execution_count": None}


def test_skeleton_status_and_russian_notebook(tmp_path):
    p, nb = _nb(tmp_path, [_md("title", "# Relief displacement"), _code("setup", "v = aerophoto.setup(RECORD_BOOK)"),
                           _md("theory", "A point above the plane moves *outwards*.")])
    st = prose.skeleton(p)
    path = prose.translation_path(p)
    assert path == tmp_path / "ru" / "03_demo.md" and path.exists()
    assert st.todo == ["title", "theory"] and not st.complete
    blocks = prose.read_translations(path)
    assert [b.cell for b in blocks] == ["title", "theory"] and all(b.todo for b in blocks)
    # the translator writes the Russian text
    done = [prose.Block("title", blocks[0].key, "# Смещение точек за рельеф"),
            prose.Block("theory", blocks[1].key, "Точка над плоскостью смещается *от центра*.")]
    prose.write_translations(path, done)
    assert prose.status(p).complete
    ru, left = prose.russian_notebook(nb, prose.read_translations(path))
    assert left == [] and ru["cells"][0]["source"] == "# Смещение точек за рельеф"
    assert ru["cells"][1]["source"] == 'v = aerophoto.setup(RECORD_BOOK, lang="ru")'
    assert nb["cells"][0]["source"] == "# Relief displacement"        # the English notebook unchanged
    # the English changes: the translation is stale, the skeleton keeps the old text for updating
    nb["cells"][2]["source"] = "A point above the mean plane moves outwards, along the radius."
    p.write_text(json.dumps(nb), encoding="utf-8")
    st = prose.status(p)
    assert st.stale == ["theory"] and not st.complete
    ru, left = prose.russian_notebook(nb, prose.read_translations(path))
    assert left == ["theory"] and ru["cells"][2]["source"].startswith("A point")   # stale: the English stays
    st = prose.skeleton(p)
    assert st.todo == ["theory"]
    text = {b.cell: b.text for b in prose.read_translations(path)}["theory"]
    assert text.startswith(prose.UPDATE) and "от центра" in text and "along the radius" in text


def test_key_ignores_surrounding_blank_lines_only():
    assert prose.cell_key("abc\n") == prose.cell_key(["a", "bc"]) != prose.cell_key("abd")
