// The page side of a live demo (aerophoto.fit.page_sensor): what the kernel cannot see from where it runs.
//
// * size: the demo's width, the window's size and the top of the figure's row within the demo, sent to the
//   kernel (the trait `box`) whenever they change, so the figure is drawn at the size of its container;
// * memory: the lecture pages' projector mode, kept in the browser's localStorage under the key `store`
//   (empty: not remembered) and restored when a page opens;
// * names: every slider handle and dropdown of the demo gets its label ("f, mm") as its accessible name
//   (ipywidgets 8.1 renders the label beside the control but does not tie the two together);
// * folds: a folded table (<details data-fold>) stays open or closed as the reader left it when the demo
//   replaces its tables after a slider move;
// * landmarks (Voilà only): the page's cells are its main region and its language is the book's.
// Nothing here is needed for the demo to work: without it the figure keeps its natural size.

function debounce(fn, ms) {
  let timer = null;
  return () => {
    clearTimeout(timer);
    timer = setTimeout(fn, ms);
  };
}

function nameControls(root) {
  root.querySelectorAll(".widget-slider").forEach((slider) => {
    const label = slider.querySelector(".widget-label");
    const name = label ? label.textContent.trim() : "";
    if (!name) return;
    const handle = slider.querySelector(".noUi-handle");
    if (handle && handle.getAttribute("aria-label") !== name) handle.setAttribute("aria-label", name);
    const readout = slider.querySelector(".widget-readout");
    if (readout && readout.getAttribute("aria-label") !== name) readout.setAttribute("aria-label", name);
  });
  root.querySelectorAll(".widget-dropdown, .widget-select").forEach((box) => {
    const label = box.querySelector(".widget-label");
    const name = label ? label.textContent.trim() : "";
    const select = box.querySelector("select");
    if (select && name && select.getAttribute("aria-label") !== name) select.setAttribute("aria-label", name);
  });
}

function markPage(model) {
  if (!document.body || !document.body.dataset.voila) return;
  const cells = document.getElementById("rendered_cells");
  if (cells && !cells.getAttribute("role")) cells.setAttribute("role", "main");
  const lang = model.get("lang");
  if (lang && document.documentElement.lang !== lang) document.documentElement.lang = lang;
}

function render({ model, el }) {
  el.classList.add("aerophoto-sensor");
  let root = null;
  const folds = new Map();  // data-fold → open

  const applyFolds = () => {
    if (!root) return;
    root.querySelectorAll("details[data-fold]").forEach((d) => {
      const key = d.dataset.fold;
      if (!folds.has(key)) folds.set(key, d.open);
      else if (d.open !== folds.get(key)) d.open = folds.get(key);
    });
  };
  const onToggle = (e) => {
    const d = e.target;
    if (d && d.tagName === "DETAILS" && d.dataset.fold) folds.set(d.dataset.fold, d.open);
  };
  const names = debounce(() => root && nameControls(root), 40);
  const mutations = new MutationObserver(() => {
    applyFolds();  // at once, before the page paints the new table
    names();
  });

  const measure = () => {
    if (!root) {
      root = el.closest(".aerophoto-demo");
      if (!root) return;
      root.addEventListener("toggle", onToggle, true);
      mutations.observe(root, { childList: true, subtree: true });
      applyFolds();
      nameControls(root);
      markPage(model);
      for (const sel of [".aerophoto-band", ".aerophoto-side"]) {
        const part = root.querySelector(sel);
        if (part) sizes.observe(part);
      }
    }
    const box = el.getBoundingClientRect();
    if (box.width < 1) return;  // not on screen (a hidden tab): keep the size it had
    const main = root.querySelector(".aerophoto-main");
    const top = main ? main.getBoundingClientRect().top - root.getBoundingClientRect().top : 0;
    const side = root.querySelector(".aerophoto-side");
    const sideW = side ? side.getBoundingClientRect().width : 0;
    const sideH = side ? side.scrollHeight : 0;
    const value = [Math.floor(box.width), window.innerWidth, window.innerHeight, Math.round(top),
      Math.round(sideW), Math.round(sideH)];
    const old = model.get("box") || [];
    // a few pixels either way (a scroll bar coming and going) are not a new size
    const same = old.length === value.length && value.every((v, i) => Math.abs(v - old[i]) < (i === 1 || i === 2 ? 1 : 6));
    if (same) return;
    model.set("box", value);
    model.save_changes();
  };
  const later = debounce(measure, 120);
  const sizes = new ResizeObserver(later);
  sizes.observe(el);
  window.addEventListener("resize", later);

  const store = model.get("store");
  const remember = () => {
    try {
      window.localStorage.setItem(store, model.get("projector") ? "1" : "0");
    } catch (e) { /* storage switched off: the mode is not remembered */ }
  };
  if (store) {
    let saved = null;
    try {
      saved = window.localStorage.getItem(store);
    } catch (e) { /* storage switched off */ }
    if (saved !== null && (saved === "1") !== model.get("projector")) {
      model.set("projector", saved === "1");
      model.save_changes();
    }
    model.on("change:projector", remember);
  }
  return () => {
    sizes.disconnect();
    mutations.disconnect();
    window.removeEventListener("resize", later);
    if (store) model.off("change:projector", remember);
    if (root) root.removeEventListener("toggle", onToggle, true);
  };
}

export default { render };
