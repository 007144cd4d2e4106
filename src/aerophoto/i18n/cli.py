"""The command line's words in Russian: ``aerophoto-course --help`` and what its commands print.

Keys are the English help texts of :mod:`aerophoto.course.cli` (and the report's options it includes) and the
templates of its messages (``str.format`` fields).
"""

from __future__ import annotations

__all__ = ["MESSAGES"]

_HELP = {
    "The aerophoto course over nbgrader: student workbook, teacher's copy, checks, generate, import, autograde (sandboxed, trusted scores), gradebook, feedback.":
        "Курс aerophoto на nbgrader: рабочая тетрадь студента, экземпляр преподавателя, проверки, генерация, "
        "импорт, автопроверка (в песочнице, доверенные баллы), ведомость, отзывы.",
    "show this help message and exit": "показать эту справку и выйти",
    "the course folder (default: $AEROPHOTO_COURSE or ./course)": "папка курса (по умолчанию: $AEROPHOTO_COURSE или ./course)",
    "the student book's notebooks (default: ./notebooks)": "тетради учебника студента (по умолчанию: ./notebooks)",
    "CSV student_id,record_book (default: <course>/roster.csv if present)":
        "CSV student_id,record_book (по умолчанию: <course>/roster.csv, если есть)",
    "run notebooks WITHOUT the sandbox, with your own rights (a developer's escape hatch for notebooks you trust; never for submissions)":
        "выполнять тетради БЕЗ песочницы, с вашими правами (лазейка разработчика для тетрадей, которым вы "
        "доверяете; никогда — для присланных работ)",
    "refuse at once when another aerophoto-course run holds the course folder (default: wait for it)":
        "сразу отказать, если папку курса занимает другой запуск aerophoto-course (по умолчанию: ждать)",
    "copy the student book into workbook/ (self-study)": "скопировать учебник студента в workbook/ (самостоятельная работа)",
    "JupyterLab for the student's workbook, without nbgrader's authoring tools":
        "JupyterLab для рабочей тетради студента, без инструментов автора nbgrader",
    "the solved teacher's copy of every chapter (for projecting)":
        "решённый экземпляр преподавателя для каждой главы (для показа на проекторе)",
    "maintenance: remove solution blocks from the notebooks' answer cells (re-runnable)":
        "обслуживание: удалить блоки решений из ячеек ответов тетрадей (можно повторять)",
    "run notebooks in the sandbox; pass/fail per task by the trusted check (exit 1 on a failure, 2 when nothing could be verified)":
        "выполнить тетради в песочнице; зачёт/незачёт по заданиям по доверенной проверке (код 1 при ошибке, 2 — "
        "если ничего не удалось проверить)",
    "nbgrader source (reference solutions) and student versions into <course>":
        "исходники nbgrader (эталонные решения) и версии для студентов в <course>",
    "copy an LMS export into <course>/submitted": "скопировать выгрузку из LMS в <course>/submitted",
    "autograde every student and chapter in the sandbox (nbgrader)":
        "автопроверка всех студентов и глав в песочнице (nbgrader)",
    "build the browser book: a JupyterLite site (Pyodide) of the workbook, the lecture index and the package, offline from pinned, hash-checked inputs":
        "собрать учебник для браузера: сайт JupyterLite (Pyodide) с рабочей тетрадью, указателем лекций и пакетом, "
        "офлайн из закреплённых, проверенных по хешу файлов",
    "build the web book: every chapter readable in English and Russian with its figures, formulas and search, the browser book beside it, and the PDFs, offline from pinned inputs":
        "собрать веб-книгу: каждая глава для чтения на русском и английском, с рисунками, формулами и поиском, рядом "
        "— книга для браузера и PDF, офлайн из закреплённых файлов",
    "the site's folder (default: _book)": "папка сайта (по умолчанию: _book)",
    "build tools and executed chapters kept between builds (default: $AEROPHOTO_SITE_CACHE or ~/.cache/aerophoto-site)":
        "средства сборки и выполненные главы, сохраняемые между сборками (по умолчанию: $AEROPHOTO_SITE_CACHE или "
        "~/.cache/aerophoto-site)",
    "the course hub's address (https://hub.example.edu): adds \"open on the course hub\" to every chapter":
        "адрес сервера курса (https://hub.example.edu): добавляет к каждой главе «открыть на сервере курса»",
    "a browser book already built (aerophoto-course lite --out DIR) to ship instead of building one":
        "уже собранная книга для браузера (aerophoto-course lite --out DIR), чтобы не собирать её заново",
    "leave out the printed books (PDF)": "не собирать печатные книги (PDF)",
    "the student's course report (guide §15, PDF and HTML) and fotoschema sheet from their workbook, read without running it (no course set-up needed)":
        "пояснительная записка студента (пособие §15, PDF и HTML) и лист фотосхемы по его рабочей тетради, "
        "прочитанной без выполнения (настройка курса не нужна)",
    "export the grades and flags as CSV": "выгрузить оценки и пометки в CSV",
    "HTML feedback per student (nbgrader)": "отзывы в HTML для каждого студента (nbgrader)",
    "folder (default: workbook/ beside notebooks/)": "папка (по умолчанию: workbook/ рядом с notebooks/)",
    "notebook to open (default: workbook/00_start_here.ipynb)": "тетрадь для открытия (по умолчанию: workbook/00_start_here.ipynb)",
    "after --: passed on to JupyterLab": "после --: передаётся JupyterLab",
    "folder (default: <course>/teacher)": "папка (по умолчанию: <course>/teacher)",
    "notebooks folder (default: --notebooks)": "папка тетрадей (по умолчанию: --notebooks)",
    "only say what would change": "только сказать, что изменится",
    "per-cell limit, s (default 120)": "предел на ячейку, с (по умолчанию 120)",
    "check for this record-book number (default: the notebook's first cell, else the remembered one)":
        "проверить для этого номера зачётной книжки (по умолчанию: из первой ячейки тетради, иначе запомненный)",
    "only this chapter (repeatable)": "только эта глава (можно повторять)",
    "only this student (repeatable)": "только этот студент (можно повторять)",
    "re-grade submissions already graded": "перепроверить уже проверенные работы",
    "per-cell limit, s (default: the config's, 120)": "предел на ячейку, с (по умолчанию: из конфигурации, 120)",
    "grade this many submissions at once, each job in its own process and sandbox uid (default 1; up to 14; the grades are the same)":
        "проверять столько работ одновременно, каждую в своём процессе и с своим uid песочницы (по умолчанию 1; "
        "до 14; оценки те же)",
    "the site's folder (default: _site)": "папка сайта (по умолчанию: _site)",
    "downloads kept between builds (default: $AEROPHOTO_LITE_CACHE or ~/.cache/aerophoto-lite)":
        "загрузки, сохраняемые между сборками (по умолчанию: $AEROPHOTO_LITE_CACHE или ~/.cache/aerophoto-lite)",
    "the folder of your notebooks (default: workbook/)": "папка ваших тетрадей (по умолчанию: workbook/)",
    "where to write (default: <workbook>/report)": "куда записать (по умолчанию: <workbook>/report)",
    'your name, for the title page and the sheet ("Иванов И. И.")': "ваше имя для титульного листа и листа фотосхемы («Иванов И. И.»)",
    'your group ("ЗиК 31")': "ваша группа («ЗиК 31»)",
    "the record-book number (default: RECORD_BOOK in the notebooks' first cell)":
        "номер зачётной книжки (по умолчанию: RECORD_BOOK в первой ячейке тетрадей)",
    "the teacher who checks it (the sheet's «Проверил»)": "преподаватель, который проверяет (графа «Проверил»)",
    "the supervisor who checks it (the title page, the sheet's «Проверил»)":
        "руководитель, который проверяет работу (титульный лист, графа «Проверил» листа)",
    "the title page's topic (default: the course's)": "тема на титульном листе (по умолчанию: тема курсовой работы)",
    "the note's language (default: ru)": "язык записки (по умолчанию: ru)",
    "compute everything afresh (default: keep the slow parts in your own verified cache)":
        "вычислить всё заново (по умолчанию медленные части берутся из вашего проверенного кэша)",
    "the report's date, YYYY-MM-DD (default: today)": "дата записки, ГГГГ-ММ-ДД (по умолчанию: сегодня)",
    "the title page's university (default: the guide's, PGUAS)": "вуз на титульном листе (по умолчанию: из пособия, ПГУАС)",
    "the title page's department": "кафедра на титульном листе",
    "the city on the title page (default: Пенза)": "город на титульном листе (по умолчанию: Пенза)",
    "do not draw the fotoschema sheet": "не строить лист фотосхемы",
    "write only the HTML page (no Typst needed)": "записать только страницу HTML (Typst не нужен)",
    "CSV file (default: <course>/grades.csv)": "файл CSV (по умолчанию: <course>/grades.csv)",
    "a row per student × chapter (default) or per student": "строка на студента × главу (по умолчанию) или на студента",
}

_MESSAGES = {
    "aerophoto-course {cmd}: {error}": "aerophoto-course {cmd}: {error}",
    "workbook: {n_new} chapter(s) written, {n_kept} kept as they were":
        "workbook: записано глав: {n_new}, оставлено как было: {n_kept}",
    ", {n_failed} skipped": ", пропущено: {n_failed}",
    "autograde: --jobs {jobs} is not valid; expected 1 … {max_jobs}":
        "autograde: --jobs {jobs} недопустимо; ожидается 1 … {max_jobs}",
    "autograde: no submissions in {folder} — run aerophoto-course import first":
        "autograde: в {folder} нет работ — сначала выполните aerophoto-course import",
    "autograde: {n} submission(s) could not be graded: {which} (see {log})":
        "autograde: не удалось проверить работ: {n}: {which} (см. {log})",
    "gradebook: {rows} row(s), {flagged} flagged → {dest}": "gradebook: строк: {rows}, с пометками: {flagged} → {dest}",
    "{path}: no such notebook": "{path}: нет такой тетради",
    "{path}: {problem}": "{path}: {problem}",
    "{path}: could not be run ({error})": "{path}: не удалось выполнить ({error})",
    # aerophoto.course.check.print_check
    "  {mark} {task} ({points:g} pt)": "  {mark} {task} ({points:g} б.)",
    "  ✗ cell {cell}: {error}": "  ✗ ячейка {cell}: {error}",
    "  {n} of {total} task(s) passed": "  выполнено заданий: {n} из {total}",
    "; {n} cell error(s)": "; ошибок в ячейках: {n}",
}

#: English → Russian
MESSAGES = {**_HELP, **_MESSAGES}
