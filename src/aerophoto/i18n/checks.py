"""The answer checks' messages in Russian (:mod:`aerophoto.checks`): ✓ lines, "no answer yet", the kinds of mistake.

Keys are the English templates with ``str.format`` fields; both languages carry the same fields.
"""

from __future__ import annotations

__all__ = ["MESSAGES", "UNITS"]

#: the tasks' units (``Answer.unit``), shown in "(in mm)"; kept apart from MESSAGES so a lone "m" in a figure
#: (a point's name) is never taken for metres
UNITS = {
    "m": "м", "mm": "мм", "km": "км", "s": "с", "h": "ч", "µm": "мкм", "%": "%", "°": "°", "″": "″",
    "(scale denominator)": "(знаменатель масштаба)",
}

_UNIT_FACTORS = {
    "a factor of 1000 — metres vs kilometres, or mm vs m?": "в 1000 раз — метры вместо километров или мм вместо м?",
    "a factor of 1/1000 — kilometres vs metres, or m vs mm?": "в 1/1000 раза — километры вместо метров или м вместо мм?",
    "a factor of 10 — centimetres vs millimetres?": "в 10 раз — сантиметры вместо миллиметров?",
    "a factor of 1/10 — millimetres vs centimetres?": "в 1/10 раза — миллиметры вместо сантиметров?",
    "a factor of 100 — a fraction vs a percentage?": "в 100 раз — доля вместо процентов?",
    "a factor of 1/100 — a percentage vs a fraction?": "в 1/100 раза — проценты вместо доли?",
    "a factor of 3600 — seconds vs hours?": "в 3600 раз — секунды вместо часов?",
    "a factor of 1/3600 — hours vs seconds?": "в 1/3600 раза — часы вместо секунд?",
    "a factor of 3.6 — km/h vs m/s?": "в 3,6 раза — км/ч вместо м/с?",
    "a factor of 1/3.6 — m/s vs km/h?": "в 1/3,6 раза — м/с вместо км/ч?",
    "a factor of 60 — minutes vs hours, or arc-minutes vs degrees?":
        "в 60 раз — минуты вместо часов или угловые минуты вместо градусов?",
    "a factor of 1/60 — hours vs minutes?": "в 1/60 раза — часы вместо минут?",
    "a factor of 57.3 — degrees vs radians?": "в 57,3 раза — градусы вместо радианов?",
    "a factor of 1/57.3 — radians vs degrees?": "в 1/57,3 раза — радианы вместо градусов?",
}

_ROUNDING = {
    "the guide rounds this count up (to the larger whole number)":
        "пособие округляет это число вверх (до большего целого)",
    "the guide rounds this count down (whole items only)": "пособие округляет это число вниз (только целые)",
    "the guide rounds this count to the nearest whole number": "пособие округляет это число до ближайшего целого",
    "count every one (a whole number)": "сосчитайте каждый (целое число)",
}

_DIAGNOSES = {
    "the size is right but the sign is wrong — check the guide's sign convention.":
        "величина верна, но знак неверен — проверьте правило знаков пособия.",
    "one too few — the guide rounds this count up (to the larger whole number).":
        "на одно меньше — пособие округляет это число вверх (до большего целого).",
    "off by one — did you forget the '+ 1' in the formula, or round the wrong way?":
        "ошибка на единицу — не забыто ли «+ 1» в формуле, или округлено не в ту сторону?",
    "your value is off by {hint}": "ваше значение отличается {hint}",
    "close, but outside the tolerance — keep more digits in the intermediate steps.":
        "близко, но вне допуска — сохраняйте больше знаков в промежуточных вычислениях.",
    "not right — go back to the formula and check each input.":
        "неверно — вернитесь к формуле и проверьте каждую исходную величину.",
    "this is the answer for variant {other:02d}, not yours ({mine:02d}) — check the record-book number in the first cell and use your own inputs.":
        "это ответ для варианта {other:02d}, а не вашего ({mine:02d}) — проверьте номер зачётной книжки в первой "
        "ячейке и используйте свои исходные данные.",
    "the values are right but in reverse order — keep the order the task gives.":
        "значения верны, но в обратном порядке — соблюдайте порядок, заданный в задании.",
    "the sizes are right but every sign is wrong — check the guide's sign convention.":
        "величины верны, но все знаки неверны — проверьте правило знаков пособия.",
    "every value is off by {hint}": "каждое значение отличается {hint}",
    "the values are right but not in the order the task gives.":
        "значения верны, но не в том порядке, что задан в задании.",
    " (the sign of {labels} is wrong)": " (неверен знак у {labels})",
    "{n_wrong} of {n} values are not right: {named}{detail}.": "неверно {n_wrong} из {n} значений: {named}{detail}.",
    "entry {k}": "элемент {k}",
    "check your value against the guide's tolerance.": "сравните своё значение с допуском пособия.",
    "read the task's definitions again.": "перечитайте определения в задании.",
    "one too many — the guide rounds this count down (whole items only).":
        "на одно больше — пособие округляет это число вниз (только целые).",
    "rounded the wrong way — the guide rounds this count to the nearest whole number.":
        "округлено не в ту сторону — пособие округляет это число до ближайшего целого.",
    "that is {quantity}, not what this answer asks for — read the task again.":
        "это {quantity}, а не то, что спрашивает этот ответ — перечитайте задание.",
    "off by one — count again{hint}": "ошибка на единицу — пересчитайте{hint}",
    "{name}: {a:g} is not a whole number — count them: a count is a whole number{unit_txt}.":
        "{name}: {a:g} — не целое число; сосчитайте: количество — целое число{unit_txt}.",
    "number": "число",
    "count": "количество",
    "{name}: no answer yet — replace the ... with your {noun}{unit_txt}.":
        "{name}: ответа ещё нет — замените ... своим {noun}{unit_txt}.",
    "{name}: {a} is a yes/no verdict — this task asks for a whole number.":
        "{name}: {a} — это вывод «да/нет», а задание требует целого числа.",
    "your answers do not agree with each other: {check} — each must follow from the others as the task says.":
        "ваши ответы не согласуются друг с другом: {check} — каждый должен следовать из остальных, как сказано в "
        "задании.",
    "your answers could not be compared with each other ({error}).":
        "ваши ответы не удалось сопоставить друг с другом ({error}).",
}

_LINES = {
    " (in {unit})": " (в {unit})",
    "✓ {name}: correct": "✓ {name}: верно",
    "✓ {name}: correct ({note})": "✓ {name}: верно ({note})",
    "{task} — checking {names}": "{task} — проверяются {names}",
    "(no answers yet)": "(ответов ещё нет)",
    "note: the check of {task} was given {what} instead of your variant — a cell has reused the name v (e.g. u, v = …); checked for your variant {i:02d} from the setup cell. Give that variable another name.":
        "заметка: проверке {task} передан {what} вместо вашего варианта — какая-то ячейка заняла имя v (например, "
        "u, v = …); проверено для вашего варианта {i:02d} из первой ячейки. Назовите ту переменную иначе.",
    "{message} ({task}: {n} of {total} right, {score:g} of {points:g} points)":
        "{message} ({task}: верно {n} из {total}, {score:g} из {points:g} баллов)",
    "{message} (and {more} more to put right)": "{message} (и ещё {more} исправить)",
    "  the teacher will see these flags:": "  преподаватель увидит эти отметки:",
    "    {code} — {meaning}": "    {code} — {meaning}",
    "✓ {name}: all {n} values correct": "✓ {name}: все {n} значений верны",
    "✓ {task} passed": "✓ {task} выполнено",
    "Task {nn}.{k}": "Задание {nn}.{k}",
    "{n} check(s)": "проверок: {n}",
    "No answers checked yet: run the check cell under each task.":
        "Ответы ещё не проверены: выполните ячейку проверки под каждым заданием.",
    "{n} of {total} checks passed; {tasks} task(s) passed completely":
        "пройдено проверок: {n} из {total}; полностью выполнено заданий: {tasks}",
    "{name}: no answer yet — replace the ... with your value{unit_txt}.":
        "{name}: ответа ещё нет — замените ... своим значением{unit_txt}.",
    "{name}: {answer} is a yes/no verdict — this task asks for a number{unit_txt}.":
        "{name}: {answer} — это вывод «да/нет», а задание требует число{unit_txt}.",
    "{name}: give a single value{unit_txt}, not a list of values.":
        "{name}: дайте одно значение{unit_txt}, а не список значений.",
    "{name}: {answer!r} is not a number — give a single value{unit_txt}.":
        "{name}: {answer!r} — не число; дайте одно значение{unit_txt}.",
    "{name}: the answer is nan — an operation went wrong before this line.":
        "{name}: ответ — nan; какая-то операция до этой строки дала сбой.",
    "{name}: the answer is infinite — a division by zero before this line?":
        "{name}: ответ бесконечен — деление на ноль до этой строки?",
    "{name}: {a:g} is not a whole number — a count of strips or photos must be rounded{unit_txt}.":
        "{name}: {a:g} — не целое число; число маршрутов или снимков нужно округлить{unit_txt}.",
    "{name}: {why}": "{name}: {why}",
    "{name}: no answer yet — replace the ... with your count{unit_txt}.":
        "{name}: ответа ещё нет — замените ... своим числом{unit_txt}.",
    "{name}: {a} is a yes/no verdict — this task asks for a count.":
        "{name}: {a} — это вывод «да/нет», а задание требует количество.",
    "{name}: {a!r} is not a number — give a whole number{unit_txt}.":
        "{name}: {a!r} — не число; дайте целое число{unit_txt}.",
    "{name}: the answer is {x} — an operation went wrong before this line.":
        "{name}: ответ — {x}; какая-то операция до этой строки дала сбой.",
    "{name}: {x:g} is not a whole number — {rule}.": "{name}: {x:g} — не целое число; {rule}.",
    "{name}: one too few — {rule}.": "{name}: на одно меньше — {rule}.",
    "{name}: one too many — {rule}.": "{name}: на одно больше — {rule}.",
    "{name}: give a dict {{name: value}} with the entries {entries}.":
        "{name}: дайте словарь {{имя: значение}} с элементами {entries}.",
    "{name}: no value for {missing}.": "{name}: нет значения для {missing}.",
    "{name}: unexpected entries {extra} — use the names the task gives.":
        "{name}: лишние элементы {extra} — используйте имена из задания.",
    "{name}: no answer yet — replace the ... with your {n} values{unit_txt}.":
        "{name}: ответа ещё нет — замените ... своими {n} значениями{unit_txt}.",
    "{name}: give a list of {n} values{unit_txt}, one per entry.":
        "{name}: дайте список из {n} значений{unit_txt}, по одному на элемент.",
    "{name}: {n_given} values given, the task asks for {n}.": "{name}: дано значений: {n_given}, задание требует {n}.",
    "{name}: no value yet for {lab}{unit_txt}.": "{name}: ещё нет значения для {lab}{unit_txt}.",
    "{name}: {lab} is a yes/no verdict — give a number{unit_txt}.":
        "{name}: {lab} — это вывод «да/нет»; дайте число{unit_txt}.",
    "{name}: {lab} = {x!r} is not a number{unit_txt}.": "{name}: {lab} = {x!r} — не число{unit_txt}.",
    "{name}: {lab} is nan — an operation went wrong before this line.":
        "{name}: {lab} — nan; какая-то операция до этой строки дала сбой.",
    "{name}: no answer yet — replace the ... with True or False.":
        "{name}: ответа ещё нет — замените ... на True или False.",
    "{name}: {answer!r} is not a verdict — write True or False (without quotes).":
        "{name}: {answer!r} — не вывод; напишите True или False (без кавычек).",
    "{name}: the verdict is wrong — {hint}": "{name}: вывод неверен — {hint}",
    "{name}: no answer yet — replace the ... with one of {opts}.":
        "{name}: ответа ещё нет — замените ... одним из вариантов {opts}.",
    "{name}: {answer!r} is not one of the options {opts}.": "{name}: {answer!r} — не из вариантов {opts}.",
    "{name}: not this one — {hint}": "{name}: не этот — {hint}",
}

_SETUP = {  # aerophoto.book.setup's banner
    "You are running in your browser (JupyterLite): nothing is installed and nothing leaves this computer. "
    "File ▸ Save keeps your answers in this browser's storage (another browser, a private window or clearing "
    "the site's data starts afresh); to hand in, File ▸ Download gives the .ipynb to upload. Grading "
    "(nbgrader, aerophoto-course) runs only in the installed book; image matching, resampling and the "
    "Gauss–Krüger conversions use the package's own numpy/scipy versions of scikit-image and pyproj here "
    "(the same numbers, slower).":
        "Книга работает в вашем браузере (JupyterLite): ничего не установлено, и ничто не покидает этот компьютер. "
        "File ▸ Save сохраняет ответы в хранилище этого браузера (другой браузер, приватное окно или очистка "
        "данных сайта начинают с нуля); чтобы сдать работу, File ▸ Download скачивает .ipynb для отправки. "
        "Проверка (nbgrader, aerophoto-course) работает только в установленной книге; сопоставление "
        "изображений, их трансформирование и пересчёт координат Гаусса–Крюгера выполняются здесь собственными "
        "версиями пакета на numpy/scipy вместо scikit-image и pyproj (те же числа, но медленнее).",
    "(remembered from an earlier chapter: {saved})": "(запомнен из предыдущей главы: {saved})",
    "Type your record-book number in the first cell to get your own variant.":
        "Введите номер зачётной книжки в первой ячейке, чтобы получить свой вариант.",
    "aerophoto {version} · variant i = {i:02d} · record book: {record_book} {note}":
        "aerophoto {version} · вариант i = {i:02d} · зачётная книжка: {record_book} {note}",
    "f = {f:g} mm, 1/m = 1:{m:.0f}, W = {W:g} km/h, α = {alpha:g}°, λ = {lam:g}°. The code behind every figure is in the package: add ?? to a name to read it, e.g. aerophoto.geometry.ground_to_photo??":
        "f = {f:g} мм, 1/m = 1:{m:.0f}, W = {W:g} км/ч, α = {alpha:g}°, λ = {lam:g}°. Код каждого рисунка — в "
        "пакете: добавьте ?? к имени, чтобы его прочитать, например aerophoto.geometry.ground_to_photo??",
}

#: English → Russian
_FLAGS = {  # aerophoto.course.flags.FLAG_MEANINGS, as ``aerophoto-course check`` prints them
    "an answer was computed with a package function that computes the task's answer (not one of the tools its text names): the teacher sees the work was not done by hand":
        "ответ вычислен функцией пакета, которая вычисляет ответ задания (не инструментом, названным в его "
        "тексте): преподаватель видит, что работа сделана не вручную",
    "the variant was changed (RECORD_BOOK, the environment, setup or variant_for_index again): the grader grades the roster's variant and shows this":
        "вариант изменён (RECORD_BOOK, окружение, повторный setup или variant_for_index): проверка ведётся для "
        "варианта из списка группы, и это видно преподавателю",
    "a cell reused the name v, the setup cell's variant (e.g. u, v = …): nothing graded changes — the checks keep the setup cell's variant — but rename the variable":
        "ячейка заняла имя v — вариант из первой ячейки (например, u, v = …): оценка не меняется — проверки "
        "сохраняют вариант первой ячейки, — но переменную лучше переименовать",
    "a check ran for another variant than the student's: graded for the student's own":
        "проверка выполнялась для чужого варианта: оценено по варианту студента",
    "the checks or their modules were replaced or imported by hand: the grader ignores the kernel's verdict and shows this":
        "проверки или их модули подменены или импортированы вручную: проверяющий не верит вердикту ядра и "
        "показывает это",
    "exception or event hooks were installed: they could hide a failed check":
        "установлены перехватчики исключений или событий: они могли бы скрыть непройденную проверку",
    "code was run from text (exec, eval, a computed attribute name, a magic)":
        "код выполнялся из текста (exec, eval, вычисляемое имя атрибута, магическая команда)",
    "files outside the working folder, processes or the network were used":
        "использовались файлы вне рабочей папки, процессы или сеть",
    "a cell could not be analysed (too long or nested too deep)":
        "ячейку не удалось разобрать (слишком длинная или слишком глубокая вложенность)",
    "what the check cell saw and what the grader computed disagree: the kernel's word is not taken":
        "то, что видела ячейка проверки, расходится с расчётом проверяющего: слову ядра не верят",
    "a check cell left no record of its answers (it did not run, or was stopped): scored 0":
        "ячейка проверки не оставила записи ответов (не выполнялась или была остановлена): 0 баллов",
    "a check cell's record of the answers could not be read: scored 0":
        "запись ответов ячейки проверки не читается: 0 баллов",
    "the notebook (or a task) could not be graded": "тетрадь (или задание) проверить не удалось",
    "an answer cell raised an error": "ячейка ответа завершилась ошибкой",
    "a cell raised an error": "ячейка завершилась ошибкой",
    "the setup cell's RECORD_BOOK is not the student's own: graded for the student's":
        "RECORD_BOOK в первой ячейке — не студента: оценено по номеру студента",
    "the setup cell's RECORD_BOOK line is missing or not a plain number":
        "строки RECORD_BOOK в первой ячейке нет, или в ней не просто номер",
    "the roster has no record-book number for this student: nothing is graded":
        "в списке группы нет номера зачётки этого студента: ничего не оценено",
    "a locked check cell was edited or copied: restored from the release before grading":
        "заблокированная ячейка проверки изменена или скопирована: перед проверкой восстановлена из выданной версии",
    "a check cell lost its grading metadata: restored from the release before grading":
        "ячейка проверки потеряла метаданные проверки: перед проверкой восстановлена из выданной версии",
    "a check cell was deleted: its task scores 0": "ячейка проверки удалена: задание получает 0",
    "an answer cell's grading metadata was changed": "метаданные проверки у ячейки ответа изменены",
    "an answer cell lost its grading metadata": "ячейка ответа потеряла метаданные проверки",
    "an answer cell was deleted": "ячейка ответа удалена",
    "the answer code is the same as another student's": "код ответов совпадает с кодом другого студента",
    "the same record-book number came from two students' folders: neither was imported":
        "один номер зачётки пришёл из папок двух студентов: не импортирована ни одна",
    "no notebook was handed in": "тетрадь не сдана",
    "the notebook file cannot be read: scored 0": "файл тетради не читается: 0 баллов",
    "the notebook ran longer than its time limit": "тетрадь выполнялась дольше отведённого времени",
}

MESSAGES = {**_UNIT_FACTORS, **_ROUNDING, **_DIAGNOSES, **_LINES, **_SETUP, **_FLAGS}
