"""The glossary page, ``notebooks/glossary.ipynb``, and its Russian text ``notebooks/ru/glossary.md``.

Both are generated from :data:`aerophoto.i18n.glossary.TERMS` and :data:`aerophoto.book.CHAPTERS` by
``python -m aerophoto.book`` (:func:`aerophoto.book.sync_generated`; a test keeps them current): the English page
(:func:`glossary_notebook`) and, for each of its Markdown cells, a Russian block (:func:`glossary_texts` with
``lang="ru"``), so that the Russian web book shows the page whole in Russian
(:func:`aerophoto.i18n.prose.russian_notebook`).  Nothing is read or written on import.
"""

from __future__ import annotations

__all__ = ["GLOSSARY_PAGE", "GLOSSARY_NOTE", "glossary_markdown", "glossary_texts", "glossary_notebook"]

GLOSSARY_PAGE = "glossary.ipynb"
"""The glossary page in ``notebooks/`` (not a chapter: its name does not start with a number)."""

GLOSSARY_NOTE = ("<!-- generated from aerophoto.i18n.glossary and aerophoto.book.CHAPTERS by "
                 "`python -m aerophoto.book`; do not edit -->")

_HEAD = {"en": ("| English | Русский | where (chapter · source) |", "## The terms"),
         "ru": ("| Русский | English | где (глава · источник) |", "## Термины")}

_TEXT = {
    "en": {
        "title": "# Glossary · Словарь терминов\n\n"
                 "Every key term of the book in English and Russian, with the chapters where it appears. The English "
                 "chapters give the Russian term in brackets at its first use, the Russian chapters the English one; "
                 "this page collects them.",
        "language": "## Русский интерфейс · the book in Russian\n\n"
                    "Every chapter reads in English and in Russian: the Russian text is the chapters' translation "
                    "(`notebooks/ru/`), which the web book shows behind the language switch on every page and the "
                    "browser book keeps in its `ru/` folder. The sliders, tables and figures of the live demos, the "
                    "answer checks and the banner speak Russian after `v = aerophoto.setup(RECORD_BOOK, lang=\"ru\")` "
                    "in any chapter's first cell; the choice is remembered for the other chapters (`lang=\"en\"` "
                    "switches back).",
    },
    "ru": {
        "title": "# Словарь терминов · Glossary\n\n"
                 "Все ключевые термины книги по-русски и по-английски и главы, в которых они встречаются. В русском "
                 "тексте глав английский термин стоит в скобках при первом употреблении, в английском — русский; "
                 "здесь они собраны вместе.",
        "language": "## Язык книги · the book in Russian\n\n"
                    "Каждую главу можно читать по-русски и по-английски: русский текст — перевод глав "
                    "(`notebooks/ru/`); в веб-книге он открывается переключателем языка на каждой странице, в "
                    "книге для браузера лежит в папке `ru/`. Ползунки, таблицы и рисунки интерактивных "
                    "демонстраций, проверки ответов и заголовок говорят по-русски после "
                    "`v = aerophoto.setup(RECORD_BOOK, lang=\"ru\")` в первой ячейке любой главы; выбор "
                    "запоминается для остальных глав (`lang=\"en\"` возвращает английский).",
    },
}


def glossary_markdown(lang: str = "en") -> str:
    """The glossary's table: every key term English ↔ Russian and the chapters (§) where it appears.

    ``lang="en"``: English first, sorted by the English term; ``lang="ru"``: Russian first, sorted by the Russian
    term (ё with е, as Russian dictionaries do), the chapters' sources in Russian ("руководство, §4").  Generated
    from :data:`aerophoto.i18n.glossary.TERMS` (the one source).
    """
    from .book import CHAPTERS, _source
    from .i18n import language
    from .i18n.glossary import terms

    if lang not in _HEAD:
        raise ValueError(f"lang = {lang!r} is not one of {sorted(_HEAD)}")
    by_source = {c.source: c for c in CHAPTERS}
    rows = terms()
    if lang == "ru":
        rows = sorted(rows, key=lambda x: (x.ru.casefold().replace("ё", "е"), x.en.casefold()))
    lines = [_HEAD[lang][0], "|---|---|---|"]
    with language(lang):
        for term in rows:
            where = ", ".join(f"[{by_source[s].number} · {_source(by_source[s])}]({by_source[s].notebook})"
                              if s in by_source else _other_source(s) for s in term.where)
            first, second = (term.en, term.ru) if lang == "en" else (term.ru, term.en)
            lines.append(f"| {first} | {second} | {where} |")
    return "\n".join(lines)


def _other_source(source: str) -> str:
    """A source no chapter has (the guide's §15, the explanatory note) in the language in use."""
    import re

    from .i18n import t

    m = re.fullmatch(r"guide §(\d+)", source)
    return t("guide §{section}", section=int(m.group(1))) if m else source


def glossary_texts(lang: str = "en") -> dict:
    """The glossary page's Markdown cells by id (``title``, ``language``, ``terms``) in ``lang``."""
    if lang not in _TEXT:
        raise ValueError(f"lang = {lang!r} is not one of {sorted(_TEXT)}")
    return {**_TEXT[lang], "terms": f"{GLOSSARY_NOTE}\n{_HEAD[lang][1]}\n\n" + glossary_markdown(lang)}


def glossary_notebook():
    """The glossary page (English): the terms' table, and how to read the book and its demos in Russian."""
    from . import nbtools

    text = glossary_texts("en")
    return nbtools.notebook([
        nbtools.md(text["title"], id="title"),
        nbtools.code("import aerophoto\nfrom aerophoto.i18n import glossary   # this page's one source: glossary.TERMS",
                     id="setup"),
        nbtools.md(text["language"], id="language"),
        nbtools.md(text["terms"], id="terms"),
    ], title="Glossary — словарь терминов")
