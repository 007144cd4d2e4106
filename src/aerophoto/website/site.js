/* The web book's one script (aerophoto.website): a display formula wider than the page scrolls sideways; make each
   such formula reachable from the keyboard (axe-core: scrollable-region-focusable), once MathJax has typeset it. */
(function () {
  function mark() {
    document.querySelectorAll("mjx-container[display='true']").forEach(function (e) {
      if (e.scrollWidth > e.clientWidth + 1 && !e.hasAttribute("tabindex")) { e.tabIndex = 0; }
    });
  }
  window.addEventListener("load", function () {
    if (window.MathJax && MathJax.startup && MathJax.startup.promise) { MathJax.startup.promise.then(mark); }
    else { mark(); }
  });
  window.addEventListener("resize", function () { window.setTimeout(mark, 200); });
})();
