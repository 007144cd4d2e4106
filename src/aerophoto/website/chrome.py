"""The web book's own words (navigation, buttons, notes, its front and lecture pages) in English and Russian.

The chapters' prose comes from the notebooks (English) and ``notebooks/ru/*.md`` (Russian,
:mod:`aerophoto.i18n.prose`); what the site itself says is here, keyed by the English text.  :func:`say` returns
the English as written, or its Russian; a key without a Russian entry is an error (the site never mixes
languages in its own chrome).
"""

from __future__ import annotations

__all__ = ["RU", "say", "LANGS", "LANG_NAMES"]

LANGS = ("en", "ru")
#: each language's name in itself (the switch shows the other one)
LANG_NAMES = {"en": "English", "ru": "Русский"}

RU = {
    "Figure": "Рис.",
    "Table": "Таблица",
    "Live demo": "Живая демонстрация",
    "live demo": "живая демонстрация",
    "interactive tool": "интерактивный инструмент",
    "at the starting values of the guide example": "при начальных значениях примера из пособия",
    "Open this demo live": "Открыть демонстрацию вживую",
    "in the browser, nothing to install": "в браузере, ничего не устанавливая",
    "This part is not translated yet: it is shown in English.": "Этот фрагмент ещё не переведён и показан по-английски.",
    "Run this chapter in the browser": "Запустить главу в браузере",
    "Open the book in the browser": "Открыть книгу в браузере",
    "Open on the course hub": "Открыть на сервере курса",
    "The whole book as PDF": "Вся книга в PDF",
    "Aerial photogrammetry — an interactive workbook": "Аэрофотограмметрия — интерактивный практикум",
    "Chapters": "Главы",
    "Reference": "Справочник",
    "Guide for students, lecturers and instructors": "Руководство для студентов, лекторов и преподавателей",
    "Lectures in the browser": "Лекции в браузере",
    "Search the book…": "Поиск по книге…",
    "This page": "Эта страница",
    "live demos": "живые демонстрации",
    "source": "источник",
    "chapter": "глава",
    "yes": "да",
    "no": "нет",
    "Read the book": "Читать книгу",
    "the whole chapter": "глава целиком",
    "Each lecture page shows a chapter's live demos one screen each, for a projector, without the code: it opens in "
    "the browser book (JupyterLite) in the same folder, so a lecture needs no server and nothing installed. Choose "
    "Run ▸ Run All Cells once the page has opened; the demos start on the guide's worked example (variant 00).":
        "Страница лекции показывает живые демонстрации главы по одной на экран, для проектора, без кода. Она "
        "открывается в браузерной версии книги (JupyterLite) из той же папки, так что лекции не нужны ни сервер, "
        "ни установка. Когда страница откроется, выберите Run ▸ Run All Cells; демонстрации начинаются с "
        "разобранного примера пособия (вариант 00).",
    "This book is the course design in photogrammetry for land-management and cadastre students, one chapter per "
    "section of the guide, with the formulas, the guide's worked example (variant 00) recomputed, and live "
    "demonstrations. Every page here is the chapter as the student book shows it, run once on the guide's example; "
    "the button at the top of a page runs the same chapter live in your browser, with nothing to install.":
        "Эта книга — курсовое проектирование по фотограмметрии для студентов направлений «Землеустройство и "
        "кадастры», по главе на раздел пособия: формулы, пересчитанный разобранный пример пособия (вариант 00) и "
        "живые демонстрации. Каждая страница здесь — глава в том виде, в каком её показывает учебник студента, "
        "выполненная один раз на примере пособия; кнопка вверху страницы запускает ту же главу вживую прямо в "
        "браузере, ничего не устанавливая.",
    "Your own variant, the graded tasks and their checks are in the live book (the button at the top of each page) "
    "or in the installed book (the guide for students).":
        "Свой вариант, задания с оценкой и их проверки — в живой книге (кнопка вверху каждой страницы) или в "
        "установленной книге (руководство для студентов).",
    "The lecture pages": "Страницы лекций",
    "The glossary": "Словарь терминов",
    "This guide is in English for now.": "Это руководство пока написано только по-английски.",
}


def say(text: str, lang: str = "en") -> str:
    """``text`` (an English key of :data:`RU`) in ``lang``; raises ``KeyError`` for a key without its Russian."""
    if text not in RU:
        raise KeyError(f"the site's text {text!r} has no Russian in aerophoto.website.chrome.RU")
    return RU[text] if lang == "ru" else text
