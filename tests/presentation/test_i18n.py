"""Every user-facing string in English and Russian (aerophoto.i18n), and the glossary (issue 17, part 2).

English is the code's own text (the catalogue is keyed by it) and stays the default, byte for byte: the browser
tests and tests/notebooks/test_no_answers_on_screen.py find sliders by their English labels.
"""

from __future__ import annotations

import argparse
import ast
import importlib
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from aerophoto import book, i18n
from aerophoto.i18n import glossary

PKG = Path(__file__).resolve().parents[2] / "src" / "aerophoto"
CYRILLIC = re.compile(r"[А-Яа-яЁё]")
WORDS = re.compile(r"[A-Za-z]{2,}")  # a string with an English word needs a Russian entry (symbols, numbers do not)
DEMOS = [(c.number, d.cls) for c in book.CHAPTERS for d in c.demos]


@pytest.fixture(autouse=True)
def _default_language(monkeypatch):
    monkeypatch.delenv("AEROPHOTO_LANG", raising=False)
    i18n.set_language(None)
    yield
    i18n.set_language(None)


def _cls(path: str):
    module, name = path.rsplit(".", 1)
    return getattr(importlib.import_module(module), name)


def _option_labels(p) -> list[str]:
    out = []
    for o in p.options:
        label = o[0] if isinstance(o, tuple) else o
        if isinstance(label, str) and WORDS.search(label):
            out.append(label)
    return out


def _demo_strings(cls) -> list[str]:
    """What a demo shows as words: its title, hint, slider labels, groups, tooltips and choices."""
    out = [cls.title, cls.hint]
    for p in cls.params:
        out += [p.label, p.group, p.help, *_option_labels(p)]
    return [s for s in out if s]


# ----------------------------------------------------------------------------------------- the catalogue
def test_every_entry_has_both_languages_with_the_same_placeholders():
    cat = i18n.catalogue()
    assert len(cat) > 500
    for en, ru in cat.items():
        assert isinstance(en, str) and en.strip(), repr(en)
        assert isinstance(ru, str) and ru.strip(), f"empty Russian for {en!r}"
        assert i18n.placeholders(en) == i18n.placeholders(ru), f"placeholders differ: {en!r} → {ru!r}"


def test_the_areas_agree_where_they_share_a_string():
    from aerophoto.i18n import checks, cli, demos, figures, live, slips

    seen: dict = {}
    for part in (demos, figures, live, checks, slips, cli):
        for en, ru in part.MESSAGES.items():
            assert seen.setdefault(en, ru) == ru, f"{en!r}: {seen[en]!r} in one area, {ru!r} in {part.__name__}"


def test_english_is_the_default_and_the_key_itself():
    assert i18n.get_language() == "en"
    for en in list(i18n.catalogue())[:200]:
        assert i18n.t(en) is en or i18n.t(en) == en
    assert i18n.t("{name}: correct", name="H_m") == "H_m: correct"
    assert i18n.t("not in the catalogue") == "not in the catalogue"


def test_language_choice_and_its_errors(monkeypatch):
    assert i18n.set_language("RU") == "ru"
    assert i18n.t("f, mm") == "f, мм"
    monkeypatch.setenv("AEROPHOTO_LANG", "en")  # the environment wins (tests, servers)
    assert i18n.get_language() == "en" and i18n.t("f, mm") == "f, mm"
    monkeypatch.delenv("AEROPHOTO_LANG")
    with i18n.language("en"):
        assert i18n.t("Reset") == "Reset"
    assert i18n.t("Reset") == "Сброс"
    with pytest.raises(ValueError, match="lang = 'de'"):
        i18n.set_language("de")


def test_importing_reads_nothing_and_sets_nothing():
    code = ("import aerophoto.i18n as m, aerophoto.i18n.glossary; "
            "print(m._catalogue is None, m._current is None, m.get_language())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PATH": "", "HOME": "/nonexistent"}).stdout.split()
    assert out == ["True", "True", "en"]


def test_every_literal_given_to_t_has_a_russian_entry():
    """An AST scan of the package: t("…") / _t("…") / translate("…") with a literal must find its entry."""
    cat = i18n.catalogue()
    missing, calls = [], 0
    for path in sorted(PKG.rglob("*.py")):
        if "i18n" in path.parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in ("t", "_t", "_tr")
                    and node.args and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
                calls += 1
                if node.args[0].value not in cat:
                    missing.append(f"{path.relative_to(PKG)}:{node.lineno} {node.args[0].value!r}")
    assert calls > 60
    assert not missing, missing


# ----------------------------------------------------------------------------------------- the live demos
def test_every_demo_string_has_a_russian_entry():
    missing = [(cls, s) for _, cls in DEMOS for s in _demo_strings(_cls(cls)) if not i18n.has(s)]
    assert not missing, missing


@pytest.mark.parametrize(("number", "cls"), DEMOS, ids=[f"{n}-{c.rsplit('.', 1)[1]}" for n, c in DEMOS])
def test_a_demo_built_in_russian_shows_russian_labels(number, cls):
    i18n.set_language("ru")
    demo = _cls(cls)()
    try:
        demo.widget()
        for p in demo.params:
            ctl = demo.controls()[p.name]
            assert ctl.description == i18n.translate(p.label, "ru"), (p.name, ctl.description)
            if p.help:
                assert ctl.tooltip == i18n.translate(p.help, "ru")
        assert demo.reset_button.description == "Сброс"
        words = [ax.get_xlabel() for ax in demo.fig.axes] + [ax.get_ylabel() for ax in demo.fig.axes]
        english = [w for w in words if w and i18n.has(w)]  # a static label left in English
        assert not english, english
    finally:
        demo.close()


def test_switching_the_language_changes_a_demos_labels_and_table():
    from aerophoto.demos.footprint import FootprintDemo

    labels = {}
    for lang in ("en", "ru"):
        i18n.set_language(lang)
        demo = FootprintDemo()
        try:
            demo.widget()
            labels[lang] = ([c.description for c in demo.controls().values()], demo.table.value,
                            [ax.get_xlabel() for ax in demo.fig.axes])
        finally:
            demo.close()
    assert labels["en"][0] == [p.label for p in FootprintDemo.params]  # English: the registry's labels, unchanged
    assert "f, мм" in labels["ru"][0] and "f, mm" not in labels["ru"][0]
    assert "Элементы снимка" in labels["ru"][1] and "Elements of the photo" in labels["en"][1]
    assert labels["en"][2] != labels["ru"][2]


def test_the_registry_sliders_have_russian_labels():
    """The browser tests' headline sliders map through the catalogue (what tests/browser/test_russian.py moves)."""
    for c in book.CHAPTERS:
        for d in c.demos:
            for label, _key in d.sliders:
                assert i18n.has(label), label


# ----------------------------------------------------------------------------------------- the checks
def test_switching_the_language_changes_a_checks_message():
    from aerophoto import checks

    msgs = {}
    for lang in ("en", "ru"):
        i18n.set_language(lang)
        with pytest.raises(checks.WrongAnswer) as exc:
            checks.check_value("H_m", ..., 1000.0, unit="m")
        with pytest.raises(checks.WrongAnswer) as exc2:
            checks.check_value("H_m", 1.0, 1000.0, unit="m")
        msgs[lang] = (str(exc.value), str(exc2.value))
    assert msgs["en"] == ("H_m: no answer yet — replace the ... with your value (in m).",
                          "H_m: your value is off by a factor of 1/1000 — kilometres vs metres, or m vs mm?")
    assert msgs["ru"] == ("H_m: ответа ещё нет — замените ... своим значением (в м).",
                          "H_m: ваше значение отличается в 1/1000 раза — километры вместо метров или м вместо мм?")
    checks.reset()


def test_the_checks_tables_of_hints_are_translated():
    from aerophoto.course import verdict

    for text in [*verdict._UNIT_FACTORS.values(), *verdict._ROUNDING.values()]:
        assert i18n.has(text), text


def test_every_task_hint_has_a_russian_entry():
    """The mistake-kind hints the checks show: every task's slips (three variants) and verdict hints."""
    from aerophoto import tasks
    from aerophoto.variants import variant_for_index

    missing = set()
    for task in tasks.all_tasks():
        for i in (0, 5, 37):
            for per_answer in task.slips(variant_for_index(i)).values():
                missing.update(k for k in per_answer if not i18n.has(k))
        missing.update(a.hint for a in task.spec if a.hint and not i18n.has(a.hint))
    assert not missing, sorted(missing)


def test_a_task_check_speaks_russian(capsys):
    from aerophoto import checks, tasks
    from aerophoto.variants import variant_for_index

    v = variant_for_index(0)
    task = tasks.get("task-01-1")
    i18n.set_language("ru")
    checks.check_task(task.id, v, **task.answers(v))
    out = capsys.readouterr().out
    assert "верно" in out and "Задание 01.1 выполнено" in out
    with pytest.raises(checks.WrongAnswer) as exc:
        checks.check_task(task.id, v)
    assert "ответа ещё нет" in str(exc.value)
    checks.reset()


# ----------------------------------------------------------------------------------------- the command line
def _helps(ap) -> list[str]:
    out = [ap.description] if ap.description else []
    for a in ap._actions:
        if a.help and a.help is not argparse.SUPPRESS:
            out.append(a.help)
        if isinstance(a, argparse._SubParsersAction):
            out += [ca.help for ca in a._choices_actions if ca.help]
            for sp in a.choices.values():
                out += _helps(sp)
    return out


def test_the_command_lines_help_exists_in_both_languages():
    from aerophoto.course.cli import _parser

    english = _helps(_parser())
    assert not [h for h in english if not i18n.has(h)]
    i18n.set_language("ru")
    russian = _helps(_parser())
    assert len(russian) == len(english)
    assert all(CYRILLIC.search(h) for h in russian), [h for h in russian if not CYRILLIC.search(h)]


# ----------------------------------------------------------------------------------------- setup remembers
def test_setup_switches_and_remembers_the_language(tmp_path, monkeypatch):
    monkeypatch.setenv("AEROPHOTO_HOME", str(tmp_path))
    monkeypatch.delenv("AEROPHOTO_RECORD_BOOK", raising=False)
    book.setup("19-0457", live=False, quiet=True, lang="ru")
    assert i18n.get_language() == "ru"
    saved = json.loads((tmp_path / "student.json").read_text(encoding="utf-8"))
    assert saved == {"record_book": "19-0457", "lang": "ru"}
    i18n.set_language(None)
    book.setup(None, live=False, quiet=True)  # a later chapter: the remembered language
    assert i18n.get_language() == "ru"
    book.setup("19-0458", live=False, quiet=True)  # a new number keeps the language
    assert json.loads((tmp_path / "student.json").read_text(encoding="utf-8"))["lang"] == "ru"
    book.setup(None, live=False, quiet=True, lang="en")
    assert i18n.get_language() == "en" and book.remembered_language() == "en"
    with pytest.raises(ValueError, match="lang"):
        book.setup(None, live=False, quiet=True, lang="fr")


def test_a_lecture_page_does_not_remember_the_language(tmp_path, monkeypatch):
    monkeypatch.setenv("AEROPHOTO_HOME", str(tmp_path))
    book.setup(live=False, quiet=True, lecture=True, lang="ru")
    assert i18n.get_language() == "ru"
    assert not (tmp_path / "student.json").exists()


# ----------------------------------------------------------------------------------------- the glossary
def test_the_glossary_covers_every_chapters_russian_title():
    rus = {x.ru for x in glossary.terms()}
    missing = [c.title_ru for c in book.CHAPTERS if c.title_ru not in rus]
    assert not missing, missing


def test_every_glossary_term_has_both_languages_and_known_sources():
    sources = {c.source for c in book.CHAPTERS} | {"guide §15"}
    for term in glossary.terms():
        assert term.en.strip() and WORDS.search(term.en), term
        assert CYRILLIC.search(term.ru), term
        assert term.where and set(term.where) <= sources, term
    assert len(glossary.terms()) > 150
    assert glossary.lookup("Resection").ru == "обратная засечка"
    assert glossary.lookup("опасный круг").en == "danger circle"


def test_the_glossary_page_is_generated_from_the_one_source():
    nb = json.loads((PKG.parents[1] / "notebooks" / book.GLOSSARY_PAGE).read_text(encoding="utf-8"))
    text = "".join("".join(c["source"]) for c in nb["cells"])
    assert book.glossary_markdown() in text
    assert not re.match(r"^\d\d", book.GLOSSARY_PAGE)  # not a chapter (tests/course/test_book.py)
    assert "| resection | обратная засечка | [06 · guide §7](06_strip_triangulation.ipynb), " \
           "[10 · guide §11](10_ground_control.ipynb) |" in text


def test_the_russian_glossary_page_is_whole_and_russian_first():
    """The Russian book's glossary (notebooks/ru/glossary.md, generated): no cell left English, every term with
    its Russian and English forms, Russian first and in Russian order, the sources named in Russian."""
    from aerophoto import glossary_page
    from aerophoto.i18n import prose

    path = PKG.parents[1] / "notebooks" / book.GLOSSARY_PAGE
    nb, untranslated = prose.russian_notebook(json.loads(path.read_text(encoding="utf-8")),
                                              prose.read_translations(prose.translation_path(path)))
    assert untranslated == []
    st = prose.status(path)
    assert (st.missing, st.todo, st.stale) == ([], [], [])
    text = "".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    assert text.startswith("# Словарь терминов") and "The prose stays English" not in text
    rows = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line][1:]
    assert len(rows) == len(glossary.terms())
    for term in glossary.terms():
        assert any(r.startswith(f"| {term.ru} | {term.en} | ") for r in rows), term
    keys = [r.split(" | ")[0][2:].casefold().replace("ё", "е") for r in rows]
    assert keys == sorted(keys)
    assert "| обратная засечка | resection | [06 · руководство, §7](06_strip_triangulation.ipynb), " \
           "[10 · руководство, §11](10_ground_control.ipynb) |" in text
    assert "guide §" not in text.split("## Термины", 1)[1]
    with pytest.raises(ValueError, match="lang = 'de'"):
        glossary_page.glossary_texts("de")


def test_the_generated_pages_are_stable(tmp_path):
    """Generating twice changes nothing: in a copy of the book with the glossary page spoilt and its Russian text
    gone, the first pass writes both back byte for byte as the repository has them, the second finds nothing."""
    import shutil

    top = PKG.parents[1]
    shutil.copy(top / "README.md", tmp_path / "README.md")
    shutil.copytree(top / "notebooks", tmp_path / "notebooks", ignore=shutil.ignore_patterns(".*", "__pycache__"))
    page, ru = tmp_path / "notebooks" / book.GLOSSARY_PAGE, tmp_path / "notebooks" / "ru" / "glossary.md"
    page.write_text(page.read_text(encoding="utf-8").replace("Словарь терминов", "Glossary"), encoding="utf-8")
    ru.unlink()
    first = book.sync_generated(tmp_path, write=True)
    assert sorted(first) == ["glossary.ipynb [glossary]", "ru/glossary.md [glossary, Russian]"]
    assert book.sync_generated(tmp_path, write=True) == []
    for rel in (book.GLOSSARY_PAGE, "ru/glossary.md"):
        assert (tmp_path / "notebooks" / rel).read_bytes() == (top / "notebooks" / rel).read_bytes(), rel


def test_the_russian_glossary_is_the_web_books_and_no_chapter_text():
    """The Russian web book's glossary page (aerophoto.website.chapter_notebooks) has no cell left English; the
    student's workbook treats ru/glossary.md like a chapter's Russian text (the book's source, not copied)."""
    from aerophoto.course import versions
    from aerophoto.website import chapter_notebooks

    notebooks = PKG.parents[1] / "notebooks"
    [(name, nb, untranslated)] = chapter_notebooks(notebooks, "ru", only={"glossary"})
    assert (name, untranslated) == ("glossary", [])
    assert "".join(nb["cells"][0]["source"]).startswith("# Словарь терминов · Glossary")
    assert versions._is_translation_source(notebooks / "ru" / "glossary.md")
