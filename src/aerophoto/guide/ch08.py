"""Chapter 08 · guide §9 (interpretation of aerial photos, дешифрирование аэроснимков): the conditions and table 10.

§9 prints no computed numbers.  It defines interpretation and interpretability (дешифрируемость), lists eight
conditions of photographing that decide it (:data:`CONDITIONS`), the direct keys (прямые дешифровочные признаки:
shape, size, tone, shadow) and the indirect ones (косвенные: natural, or landscape, and anthropogenic), and gives
table 10, the keys of topographic interpretation (топографическое дешифрирование) of rivers, lakes, ponds, bogs,
forest, lowlands and meadows, arable land, railways and roads (:data:`TABLE_10`).  They are kept here once, in
Russian as printed and in English (our own wording), for chapter 08; the physics of the conditions is
:mod:`aerophoto.interpretation`, the objects are on :mod:`aerophoto.site.cover`.

Transcription notes (the scan's garbling, cleaned): "технологии ческое" in the classification by content is read
**топографическое** (the next sentence defines topographic interpretation; the scan broke and misread the word);
"призна-ки", "инди-каторами" are de-hyphenated; the table's running heads ("Продолжение табл. 10",
"Окончание табл. 10") and the stray "D" and "Д" before "Болота" and "Дороги автомобильные" are dropped; the pond's
row "Направление течения водотоков" was split over two lines.

What the book notes beside the table (chapter 08):

* **Shallows below the islands.**  Table 10 puts the shallows on the downstream side of islands (отмели находятся
  с низовой стороны островов).  That holds for the bars that trail behind an island (where the two currents meet
  again and drop their load), but an island's upstream head also collects a bar in many rivers; the key is safe
  only together with the island's shape.  The site follows the table.
* **Definition's wording.**  §9 defines interpretation as finding objects "изобразившихся на фотосхемах" (on
  photo mosaics); it applies to single photos and stereo pairs alike, as §9 itself goes on to use them.
* **Rivers widen downstream.**  Table 10's flow keys (islands narrowing downstream, tributaries at an acute angle)
  are the reliable ones; a river's own width is not a key (on the site it widens downstream, as rivers usually do).
"""

from __future__ import annotations

import pandas as pd

__all__ = ["SOURCE", "CONDITIONS", "DIRECT_KEYS", "INDIRECT_KEYS", "TABLE_10", "table_10", "conditions_table",
           "keys_table", "GROUPS"]

SOURCE = "guide §9, table 10"

#: the conditions of photographing that decide interpretability (guide §9): number, English, Russian, the gist
CONDITIONS = (
    (1, "season", "время года", "winter snow hides detail; autumn's uniform vegetation and wet soil lower the "
     "contrast; leaf-off in spring and autumn opens what is under trees but hides the vegetation itself: summer "
     "photos are the most complete"),
    (2, "time of day", "время дня", "the strength, colour and direction of light and the size, shape and direction "
     "of shadows change; the hours before noon are mostly best"),
    (3, "moisture of the objects", "влажность объектов", "the wetter, the more uniform, darker and harder to read"),
    (4, "landscape contrast", "контраст ландшафта", "helps to see boundaries sharply"),
    (5, "haze or smoke", "задымленность воздуха", "lowers contrast and detail, and so readability"),
    (6, "tilt of the negative", "угол наклона аэронегатива", "scale varies over the photo, the view changes and "
     "objects hide each other"),
    (7, "exposure time and the aircraft's speed", "длительность выдержки и скорость полёта", "decide sharpness and "
     "detail"),
    (8, "steep slopes of hills and ravines", "значительная крутизна склонов гор и оврагов", "(listed without "
     "comment)"),
)

#: direct keys (прямые дешифровочные признаки): English, Russian, what they tell (guide §9)
DIRECT_KEYS = (
    ("shape", "форма", "man-made objects have regular shapes; natural ones do not"),
    ("size", "размер", "judged relative to known objects, or measured by the photo's scale"),
    ("tone", "тон изображения", "the object's brightness within the film's sensitivity; read on a scale light, "
     "light grey, grey, …"),
    ("shadow", "тень", "gives the height and the shape in height"),
)
#: indirect keys (косвенные признаки)
INDIRECT_KEYS = (
    ("natural (landscape) keys", "природные (ландшафтные) признаки", "the links between natural objects: grass "
     "and soil, relief and geology; indicators (индикаторы) of what is not seen"),
    ("anthropogenic keys", "антропогенные признаки", "the functional links of man-made objects: position in a "
     "complex, communications"),
)

#: the groups of table 10: English, Russian
GROUPS = {"rivers": "Реки", "lakes": "Озера", "ponds": "Пруды", "bogs": "Болота", "forest": "Лес",
          "lowlands and meadows": "Низины и луга", "arable land": "Пашни", "railways": "Дороги железные",
          "roads": "Дороги автомобильные"}

#: table 10 (guide §9): group, element (English, Russian), key (English — ours, Russian — as printed), and the
#: site's object that illustrates it in chapter 08's interactive key (None: nothing on the site shows it)
TABLE_10 = (
    ("rivers", "length, width", "Длина, ширина", "measured by the photo's scale",
     "Измерение по масштабу аэрофотоснимка", "river width"),
    ("rivers", "height and steepness of banks", "Высота и крутизна берегов",
     "from the shadows and by comparison with other landforms",
     "По расположению тени и по сравнению с другими элементами рельефа", None),
    ("rivers", "outline of banks and islands, shallows", "Конфигурация берегов и островов, отмели",
     "from the shape and outlines of the image; shallows lie on the downstream side of islands",
     "По форме изображения и контурам; отмели находятся с низовой стороны островов", "island"),
    ("rivers", "depth", "Глубина", "from the tone of the water: shallow water light, deep water dark",
     "По тону изображения водной поверхности: мелководье – светлый тон, глубокая вода – темный", "shallows"),
    ("rivers", "direction of flow", "Направление течения",
     "islands narrow towards their downstream ends; tributaries enter at an acute angle",
     "По очертанию островов, суживающихся в низовых частях; по устьям притоков, впадающих под острым углом",
     "tributary"),
    ("rivers", "speed of flow", "Скорость течения",
     "from the pattern of the currents: the sharper the pattern, the faster; at high speed foam shows below an island",
     "По рисунку струй: более отчетливый рисунок – скорость выше; при высокой скорости с низовой стороны острова "
     "видна пена", "current"),
    ("lakes", "shape and size", "Форма и размеры", "from the outlines and shape of the shores; sizes by the scale",
     "По контурам и конфигурации берегов; размеры по масштабу аэрофотоснимков", "lake"),
    ("ponds", "shape and size", "Форма и размеры", "from the outlines and shape of the shores; sizes by the scale",
     "По контурам и конфигурации берегов; размеры по масштабу аэрофотоснимков", "pond"),
    ("ponds", "direction of flow of the streams", "Направление течения водотоков",
     "from where the dam is and the shape of the water surface",
     "По местоположению плотины и форме водного зеркала", "dam"),
    ("bogs", "raised bog", "Верховые",
     "on a watershed, far from streams, large; small bog lakes; peat mosses, tone uneven with uneven wetness; "
     "sometimes small sparse pines",
     "По положению в рельефе: на водоразделе, вдали от водотоков, обширные площади, есть озерки. По виду "
     "растительности: торфяно-моховые, преобладают мхи; тональность неодинаковая вследствие различной влажности; "
     "иногда редкие мелкие сосенки", "raised bog"),
    ("bogs", "low bog", "Низинные",
     "in a river valley, ribbon-shaped; sedge and reed or trees and shrubs, dense at the edges",
     "Расположены в речной долине, лентовидные в плане; растительность осоко-тростниковая или "
     "древесно-кустарниковая, по окраинам густая", "low bog"),
    ("forest", "pine", "Сосновый", "even grey tone (trees of one height); crowns convex in plan",
     "Тональность однообразная серая (деревья однородны по высоте); проекции крон выпуклые", "pine forest"),
    ("forest", "spruce", "Еловый",
     "mottled tone, darker than pine; crowns elongated with pointed tops; cones seen under the stereoscope",
     "Тональность пестрая, темнее соснового леса, проекции крон вытянутые, вершины остроконечные; в стереоскоп "
     "заметна конусообразность деревьев", "spruce forest"),
    ("forest", "deciduous", "Лиственный",
     "lighter than conifers; grainy surface of varied tone with rounded soft outlines",
     "Тональность более светлая, чем хвойного леса; поверхность зернистая различной тональности с округлыми "
     "мягкими очертаниями", "deciduous forest"),
    ("forest", "shrub", "Кустарник", "lighter than forest, finer grain, shorter shadows",
     "Тональность светлее, чем у леса, зернистость мельче, тень короче", "shrub"),
    ("lowlands and meadows", "state of the surface", "Состояние поверхности",
     "waterlogging shows as sun glint from water; a meadow is even grey, a mown one lighter, a wet one darker; "
     "haystacks and sparse shrub mark a meadow",
     "Заболачивание низин дешифрируется по отражению солнца от водной поверхности: тональность луга ровная серая, "
     "скошенный луг – светлее, мокрый – имеет темный оттенок; признаки луга – стога сена, редкий кустарник",
     "haystacks"),
    ("arable land", "shape, size, boundaries", "Форма, размеры, границы",
     "straight boundaries, even tone, furrowed surface; sizes by the scale",
     "Прямолинейные границы, равномерный тон, бороздчатая поверхность, размеры по масштабу", "arable land"),
    ("railways", "roadbed", "Земляное полотно",
     "even width; long straights joined by curves of large radius; rails visible at large scales",
     "Равномерная ширина; прямые участки значительной длины, сопрягаемые кривыми большого радиуса; на "
     "аэрофотоснимках крупного масштаба видны рельсовые нити", "railway"),
    ("roads", "roadbed", "Земляное полотно",
     "wide, more winding than a railway, curves of small radius on low embankments, edged by ditches",
     "Широкое полотно, более извилистое, чем железнодорожное, кривые малых радиусов при низких насыпях, окантовано "
     "кюветами", "asphalt road"),
    ("roads", "surface", "Дорожное покрытие", "dark tone — asphalt; light — gravel",
     "Темный тон – асфальтовое, светлый – гравийное", "gravel road"),
)


def table_10() -> pd.DataFrame:
    """Table 10 as printed (Russian) with our English beside it."""
    return pd.DataFrame([{"group": f"{g} ({GROUPS[g]})", "element": f"{e} ({e_ru})", "key": k, "признаки": k_ru}
                         for g, e, e_ru, k, k_ru, _ in TABLE_10])


def conditions_table() -> pd.DataFrame:
    """§9's conditions of photographing."""
    return pd.DataFrame([{"condition": f"{en} ({ru})", "what it does": gist} for _, en, ru, gist in CONDITIONS],
                        index=pd.Index([c[0] for c in CONDITIONS], name="§9"))


def keys_table() -> pd.DataFrame:
    """Direct and indirect keys."""
    rows = [{"kind": "direct (прямой)", "key": f"{en} ({ru})", "tells": t} for en, ru, t in DIRECT_KEYS]
    rows += [{"kind": "indirect (косвенный)", "key": f"{en} ({ru})", "tells": t} for en, ru, t in INDIRECT_KEYS]
    return pd.DataFrame(rows)
