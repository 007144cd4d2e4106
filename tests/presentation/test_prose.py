"""The chapters' Russian text (aerophoto.i18n.prose): blocks keyed by cell id and the English text's hash."""

import json
import re

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


def test_every_chapter_has_its_russian_text_complete():
    """Every chapter of the registry (and the lecture index and pages): a Russian block for each Markdown cell, translated and
    keyed to the English text as it reads now (``python -m aerophoto.i18n.prose status`` says which; ``skeleton NN`` marks them)."""
    from aerophoto import book
    from conftest import NOTEBOOKS

    found = {p.name for p in NOTEBOOKS.glob("[0-9][0-9]_*.ipynb")}
    assert found == {c.notebook for c in book.CHAPTERS}      # the registry names every chapter notebook
    pages = ([NOTEBOOKS / c.notebook for c in book.CHAPTERS] + [NOTEBOOKS / book.LECTURE_INDEX]
             + [NOTEBOOKS / book.lecture_page(c) for c in book.CHAPTERS if c.demos])
    incomplete = [st.line() for st in map(prose.status, pages) if not st.complete]
    assert incomplete == []


def test_the_registry_speaks_russian():
    """Chapter 00's Russian table of chapters and the lecture index's table of demos are built from these: every
    chapter's topic and every live demo's name, move and what the class sees has its Russian (aerophoto.i18n.chapters)."""
    from aerophoto import book
    from aerophoto.i18n import has
    from conftest import NOTEBOOKS

    texts = [s for c in book.CHAPTERS for s in (c.title, *(x for d in c.demos for x in (d.name, d.move, d.sees)))]
    words = re.compile(r"[A-Za-z]{2,}")   # a text of symbols alone ("x") reads the same in Russian
    assert [s for s in texts if words.search(s) and not has(s)] == []
    demos = book.lecture_table_markdown(lang="ru")
    assert "| Лупа на снимке | метка, на которую навести лупу" in demos and "([вся глава](08_interpretation.ipynb))" in demos
    assert "[08 · Дешифрирование аэроснимков: условия фотографирования" in demos and "(руководство, §9)]" in demos
    page = {b.cell: b.text for b in prose.read_translations(NOTEBOOKS / "lectures" / "ru" / "08_interpretation.md")}
    assert page["demo-loupe-notes"].startswith("**Лупа на снимке.** Что двигать: метка, на которую навести лупу")
    assert "[вся глава 08 — с теорией и заданиями](../08_interpretation.ipynb) · руководство, §9 ·" in page["links"]
    table = book.chapter_table_markdown(lang="ru")
    assert table.splitlines()[0] == "| тетрадь | источник | тема | интерактивные демонстрации |"
    assert "| руководство, §9 | дешифрирование аэроснимков" in table and "| статья 003 |" in table
    assert "Лупа на снимке" in table and "guide §" not in table


def test_the_russian_chapter_table_follows_the_registry(tmp_path, monkeypatch):
    """A chapter added to the registry: chapter 00's Russian block is stale until regenerated, then has the new row
    and the English cell's key (so the Russian chapter 00 shows it, not the English table)."""
    import shutil

    from aerophoto import book
    from conftest import NOTEBOOKS

    ru = tmp_path / "notebooks" / "ru" / "00_start_here.md"
    ru.parent.mkdir(parents=True)
    shutil.copy(NOTEBOOKS / "ru" / "00_start_here.md", ru)
    extra = book.Chapter("18", "test_extra", "relief displacement", "смещение точек за рельеф", section=4, demos=(
        book.Demo("demo-x", "aerophoto.demos.ray.RayDemo", "One ray of a vertical photo", "x", "the ray", ()),))
    monkeypatch.setattr(book, "CHAPTERS", (*book.CHAPTERS, extra))
    english, russian = next(c for _, kind, place, c in book._generated(tmp_path)
                            if kind == "translation" and place == "chapters")
    assert prose.sync_block(ru, "chapters", english, russian, write=False)
    assert prose.sync_block(ru, "chapters", english, russian, write=True)
    assert not prose.sync_block(ru, "chapters", english, russian, write=False)
    block = {b.cell: b for b in prose.read_translations(ru)}["chapters"]
    assert block.key == prose.cell_key(english) and not block.todo
    assert ("| [`18_test_extra`](18_test_extra.ipynb) | руководство, §4 | смещение точек за рельеф | "
            "Один луч горизонтального снимка |") in block.text
    assert len(prose.read_translations(ru)) == len(prose.read_translations(NOTEBOOKS / "ru" / "00_start_here.md"))
