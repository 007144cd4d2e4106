"""The book's key terms, English ↔ Russian, with where they appear: the one source of the glossary page.

Collected from the Russian terms the chapters put beside their English ones (at a key term's first use) and
from the chapters' Russian titles (:data:`aerophoto.book.CHAPTERS`).  ``where`` names the sources as the
chapter registry does (``"guide §4"``, ``"article 001"``); :func:`aerophoto.book.glossary_markdown` turns them
into links to the chapters and ``python -m aerophoto.book`` writes ``notebooks/glossary.ipynb``.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Term", "TERMS", "CHAPTER_TITLES", "terms", "lookup"]


@dataclass(frozen=True)
class Term:
    """One glossary entry: the English term, the Russian term, the sources where the book uses it."""

    en: str
    ru: str
    where: tuple = ()


def _t(en: str, ru: str, *where: str) -> Term:
    return Term(en, ru, tuple(where))


#: the chapters' topics and their Russian titles (one per chapter, as in aerophoto.book.CHAPTERS)
CHAPTER_TITLES = (
    _t("your variant; central projection", "задание; центральная проекция", "guide §1"),
    _t("planning the aerial survey", "расчёт параметров аэросъёмки", "guide §2"),
    _t("judging the photos' quality", "оценка качества материалов", "guide §3"),
    _t("relief displacement", "смещение точек за рельеф", "guide §4"),
    _t("tilt displacement", "смещения за угол наклона", "guide §5"),
    _t("single-strip photo mosaic", "одномаршрутная фотосхема", "guide §6"),
    _t("strip phototriangulation", "фототриангуляционный ряд", "guide §7"),
    _t("the lens-mirror stereoscope; studying the stereo model", "линзово-зеркальный стереоскоп; изучение стереомодели",
       "guide §8"),
    _t("interpreting aerial photos", "дешифрирование аэроснимков", "guide §9"),
    _t("correcting a plan by mutual projective grids", "корректировка плана методом взаимно-проектных сеток",
       "guide §10"),
    _t("design of ground control", "проект планово-высотной привязки", "guide §11"),
    _t("rectification of photos", "фототрансформирование", "guide §12"),
    _t("phototriangulation", "фототриангуляция", "guide §7", "guide §13", "article 001"),
    _t("aerial and space photos in soil mapping", "применение аэро- и космических снимков при почвенном картографировании",
       "guide §14"),
    _t("accuracy of phototriangulation networks", "точность фототриангуляционных сетей", "article 001"),
    _t("bundle block phototriangulation", "блочная фототриангуляция по методу связок", "article 002"),
    _t("drawing contours from DEM points", "рисовка горизонталей по точкам ЦМР", "article 000"),
    _t("analysis of planimetric accuracy in map updating", "анализ плановой точности при обновлении карт", "article 003"),
)

#: the key terms the chapters introduce, with the Russian term they put beside them
TERMS = CHAPTER_TITLES + (
    _t("course design", "курсовая работа", "guide §1"),
    _t("record-book number", "номер зачётной книжки", "guide §1"),
    _t("central projection", "центральная проекция", "guide §1"),
    _t("aerial camera", "аэрофотоаппарат, АФА", "guide §1", "guide §3"),
    _t("flying height", "высота фотографирования", "guide §1", "guide §2", "guide §3"),
    _t("photo scale", "масштаб аэрофотосъёмки", "guide §2"),
    _t("survey area", "площадь участка", "guide §2"),
    _t("forward overlap", "продольное перекрытие", "guide §2", "guide §3"),
    _t("side overlap", "поперечное перекрытие", "guide §2", "guide §3"),
    _t("working area (of a photo)", "рабочая площадь снимка", "guide §2", "guide §6"),
    _t("photo base, air base", "базис фотографирования", "guide §2", "guide §8"),
    _t("distance between strips", "расстояние между маршрутами", "guide §2"),
    _t("route length", "длина пути самолёта", "guide §2"),
    _t("image smear, image motion", "смаз изображения", "guide §2", "guide §3"),
    _t("longest admissible exposure", "максимальная выдержка", "guide §2"),
    _t("explanatory note (the course report)", "пояснительная записка", "guide §2", "guide §15"),
    _t("magazine", "кассета", "guide §3"),
    _t("aerial lens", "аэрофотообъектив", "guide §3"),
    _t("resolving power", "разрешающая способность", "guide §3"),
    _t("flicker method", "способ мельканий", "guide §3", "guide §6"),
    _t("rough mosaic", "накидной монтаж", "guide §3", "guide §11"),
    _t("photographic quality", "фотографическое качество", "guide §3"),
    _t("photogrammetric quality", "фотограмметрическое качество", "guide §3"),
    _t("rejected material", "брак", "guide §3"),
    _t("straightness of a strip", "прямолинейность маршрута", "guide §3"),
    _t("crab", "отклонение базиса от направления маршрута", "guide §3"),
    _t("tilt angle", "угол наклона", "guide §3", "guide §5"),
    _t("circular level", "круглый уровень", "guide §3"),
    _t("scale difference", "разномасштабность", "guide §3"),
    _t("mean object plane", "средняя предметная плоскость", "guide §4"),
    _t("plan", "план", "guide §4"),
    _t("base (on a photo)", "базис", "guide §4"),
    _t("test site", "полигон", "guide §4"),
    _t("zones", "зоны", "guide §4", "guide §5"),
    _t("fiducial marks", "координатные метки", "guide §4"),
    _t("partial scale", "частный масштаб", "guide §4", "guide §6"),
    _t("mean scale", "средний масштаб", "guide §4", "guide §6"),
    _t("nadir point", "точка надира", "guide §1", "guide §4"),
    _t("isocentre", "точка нулевых искажений", "guide §1", "guide §5"),
    _t("principal point", "главная точка", "guide §1", "guide §5"),
    _t("principal vertical", "главная вертикаль", "guide §1", "guide §5"),
    _t("photo mosaic (fotoschema)", "фотосхема", "guide §6"),
    _t("photoplan", "фотоплан", "guide §6"),
    _t("cut-out", "вырез", "guide §6"),
    _t("duplicate", "дублет", "guide §6"),
    _t("trimmings", "обрезки", "guide §6"),
    _t("correction sheet", "корректурный лист", "guide §6"),
    _t("control points (identified on the photos)", "опознаки", "guide §7", "guide §11", "article 002"),
    _t("radial triangulation", "радиальная фототриангуляция", "guide §7"),
    _t("working centre", "рабочий центр", "guide §7"),
    _t("to prick (a point)", "накалывать", "guide §7"),
    _t("initial directions", "начальные направления", "guide §7"),
    _t("direction template", "восковка направлений", "guide §7"),
    _t("resection", "обратная засечка", "guide §7", "guide §11"),
    _t("discrepancies", "невязки", "guide §7"),
    _t("error triangle", "треугольник погрешностей", "guide §7"),
    _t("free strip", "свободный ряд", "guide §7"),
    _t("reduction", "редуцирование", "guide §7", "guide §13"),
    _t("base (sheet)", "основа", "guide §7", "guide §12", "guide §13"),
    _t("stereo pair", "стереопара", "guide §8"),
    _t("stereo effect", "стереоэффект", "guide §8"),
    _t("direct stereo effect", "прямой стереоэффект", "guide §8"),
    _t("reverse stereo effect", "обратный стереоэффект", "guide §8"),
    _t("x-parallax", "продольный параллакс", "guide §8"),
    _t("lens-mirror stereoscope", "линзово-зеркальный стереоскоп", "guide §8"),
    _t("floating mark", "измерительная марка", "guide §8"),
    _t("stereo model", "стереомодель", "guide §8"),
    _t("parallax bar", "параллактометр", "guide §8"),
    _t("image correlation", "корреляция изображений", "guide §8"),
    _t("occluded areas", "закрытые участки", "guide §8"),
    _t("interpretation", "дешифрирование", "guide §9"),
    _t("interpretability", "дешифрируемость", "guide §9"),
    _t("topographic interpretation", "топографическое дешифрирование", "guide §9"),
    _t("direct keys", "прямые дешифровочные признаки", "guide §9", "guide §14"),
    _t("indirect keys", "косвенные признаки", "guide §9", "guide §14"),
    _t("indicators", "индикаторы", "guide §9"),
    _t("conditions of photographing", "условия фотографирования", "guide §9"),
    _t("image tone", "тон изображения", "guide §9"),
    _t("spectral reflectance", "коэффициент спектральной яркости, КСЯ", "guide §9", "guide §14"),
    _t("colour-infrared (film, photo)", "спектрозональный", "guide §9", "guide §14"),
    _t("magnifier", "лупа", "guide §9"),
    _t("texture (of the image)", "текстура, зернистость изображения", "guide §9", "guide §14"),
    _t("pattern (of the image)", "рисунок изображения", "guide §9"),
    _t("tramlines", "технологическая колея", "guide §9"),
    _t("road shoulder", "обочина", "guide §9"),
    _t("roadside ditch", "кювет", "guide §9"),
    _t("overlay technique (transparent sheets)", "дешифрирование на прозрачных основах", "guide §14"),
    _t("plan correction", "корректировка плана", "guide §10"),
    _t("mutual projective grids", "взаимно-проектные сетки", "guide §10"),
    _t("projective transformation", "проективное преобразование", "guide §10"),
    _t("central directions", "центральные направления", "guide §10"),
    _t("proportional division", "пропорциональное деление", "guide §10"),
    _t("proportional compass", "пропорциональный циркуль", "guide §10"),
    _t("ground control (of photos)", "привязка аэроснимков", "guide §11"),
    _t("control points", "опорные точки", "guide §10", "guide §11", "guide §13"),
    _t("planimetric and height control", "планово-высотная привязка", "guide §11"),
    _t("planimetric control", "плановая привязка", "guide §11"),
    _t("height control", "высотная привязка", "guide §11"),
    _t("dense control", "сплошная привязка", "guide §11"),
    _t("sparse control", "разреженная привязка", "guide §11"),
    _t("technical file", "техническое дело", "guide §11"),
    _t("direction angle", "дирекционный угол", "guide §11"),
    _t("danger circle", "опасный круг", "guide §11"),
    _t("rectification", "трансформирование", "guide §12"),
    _t("photo transformer", "фототрансформатор ФТБ", "guide §12"),
    _t("transformation points", "трансформационные точки", "guide §10", "guide §12"),
    _t("principal horizontal", "главная горизонталь", "guide §12"),
    _t("control grid", "контрольная сетка", "guide §12"),
    _t("substrate", "подложка", "guide §12"),
    _t("soil map", "почвенная карта", "guide §14"),
    _t("soil interpretation", "почвенное дешифрирование", "guide §14"),
    _t("contour soil interpretation", "контурное почвенное дешифрирование", "guide §14"),
    _t("moisture", "влажность", "guide §14"),
    _t("humus", "гумус", "guide §14"),
    _t("particle size", "размер частиц", "guide §14"),
    _t("land management", "землеустройство", "guide §14"),
    _t("upper horizon", "верхний горизонт", "guide §14"),
    _t("clods (macrostructure)", "макроструктура", "guide §14"),
    _t("particles (microstructure)", "микроструктура", "guide §14"),
    _t("vegetation", "растительность", "guide §14"),
    _t("parent rock", "почвообразующие породы", "guide §14"),
    _t("human activity", "хозяйственная деятельность", "guide §14"),
    _t("soil pit", "почвенный разрез", "guide §14"),
    _t("phototriangulation network", "фототриангуляционная сеть", "article 001"),
    _t("error accumulation", "накопление ошибок", "article 001"),
    _t("density of control points", "густота опорных точек", "article 001"),
    _t("method of continuation", "метод продолжений", "article 001"),
    _t("relative orientation", "взаимное ориентирование", "article 001", "article 002"),
    _t("gravimetric point", "пункт гравиметрических наблюдений, ПГН", "article 002"),
    _t("block phototriangulation", "блочная фототриангуляция", "article 002"),
    _t("bundle method", "метод связок", "article 002"),
    _t("collinearity equations", "уравнения коллинеарности", "article 002"),
    _t("blunders", "грубые ошибки", "article 002"),
    _t("error ellipses", "эллипсы ошибок", "article 002"),
    _t("elements of exterior orientation", "элементы внешнего ориентирования", "article 002"),
    _t("check points", "контрольные точки", "article 002"),
    _t("land-reclamation system", "мелиоративная система", "article 000"),
    _t("contours", "горизонтали", "article 000"),
    _t("contour interval", "сечение рельефа", "article 000"),
    _t("digital elevation model, DEM", "цифровая модель рельефа, ЦМР", "article 000"),
    _t("height densification", "сгущение высотного обоснования", "article 000"),
    _t("regular (grid) model", "регулярная модель", "article 000"),
    _t("structural model", "нерегулярная модель", "article 000"),
    _t("structural lines", "структурные линии", "article 000"),
    _t("thalwegs", "тальвеги", "article 000"),
    _t("watersheds", "водоразделы", "article 000"),
    _t("RMS error", "средняя квадратическая ошибка, СКО", "article 000", "article 003"),
    _t("mean error", "средняя ошибка", "article 003"),
    _t("map updating", "обновление карт", "article 003"),
    _t("digital photogrammetric station", "цифровая фотограмметрическая станция, ЦФС", "article 003"),
)


def terms() -> tuple:
    """Every term, sorted by its English form (case-insensitive), duplicates of the same pair merged."""
    merged: dict = {}
    for term in TERMS:
        key = (term.en, term.ru)
        old = merged.get(key)
        where = tuple(dict.fromkeys((*(old.where if old else ()), *term.where)))
        merged[key] = Term(term.en, term.ru, where)
    return tuple(sorted(merged.values(), key=lambda x: (x.en.casefold(), x.ru)))


def lookup(text: str) -> Term | None:
    """The entry whose English or Russian form is ``text`` (case-insensitive), or None."""
    key = text.strip().casefold()
    return next((x for x in terms() if key in (x.en.casefold(), x.ru.casefold())), None)
