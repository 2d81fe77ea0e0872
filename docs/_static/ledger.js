// The ledger's table (ledger.html): each row's explanation beneath it, across the table's width;
// filter the rows by chapter, verdict and text, and sort them by any column (click its heading;
// again to reverse). No library, nothing fetched: the site works offline. A link to a row
// (ledger.html#claim-...) shows the row, whatever the filters.
"use strict";

(function () {
  function cellText(row, index) {
    return row.cells[index] ? row.cells[index].textContent.trim() : "";
  }

  function asNumber(text) {
    const match = /^[<>]?\s*([-+]?\d*\.?\d+(?:e[-+]?\d+)?)/i.exec(text);
    return match ? parseFloat(match[1]) : NaN;
  }

  function option(select, value, label) {
    const item = document.createElement("option");
    item.value = value;
    item.textContent = label;
    select.appendChild(item);
  }

  function choice(label, name, values) {
    const wrapper = document.createElement("label");
    wrapper.className = "ledger-filter";
    wrapper.textContent = label + " ";
    const select = document.createElement("select");
    select.name = name;
    select.id = "ledger-filter-" + name;
    option(select, "", "all");
    values.forEach((value) => option(select, value, value));
    wrapper.appendChild(select);
    return [wrapper, select];
  }

  // The explanation column's cells, each moved into a row of its own beneath its row, spanning
  // the other columns, which share its part of the width (the list-table's <col> widths).
  function explainBeneath(table, index) {
    const columns = [...table.querySelectorAll("colgroup col")];
    if (columns.length) {
      const share = (col) => parseFloat(col.style.width);
      const rest = 100 - share(columns[index]);
      columns[index].remove();
      columns.splice(index, 1);
      columns.forEach((col) => { col.style.width = `${(100 * share(col)) / rest}%`; });
    }
    table.tHead.rows[0].cells[index].remove();
    const span = table.tHead.rows[0].cells.length;
    [...table.tBodies[0].rows].forEach((row) => {
      const beneath = document.createElement("tr");
      beneath.className = "ledger-explanation";
      const cell = row.cells[index];
      cell.colSpan = span;
      beneath.appendChild(cell);
      row.after(beneath);
      row.explanation = beneath;
    });
  }

  function setUp(table) {
    explainBeneath(table, [...table.tHead.rows[0].cells].findIndex(
      (cell) => cell.textContent.trim() === "explanation"));
    const headings = [...table.tHead.rows[0].cells].map((cell) => cell.textContent.trim());
    const column = (name) => headings.indexOf(name);
    const body = table.tBodies[0];
    const rows = [...body.rows].filter((row) => row.explanation);
    const pair = (row) => [row, row.explanation];
    const chapterAt = column("chapter");
    const verdictAt = column("verdict");
    const distinct = (index) => [...new Set(rows.map((row) => cellText(row, index)))];
    const chapters = distinct(chapterAt).sort((a, b) =>
      a.localeCompare(b, undefined, { numeric: true }));
    const verdicts = ["reproduces", "close", "does not reproduce", "recovered"].filter((v) =>
      distinct(verdictAt).includes(v));

    const controls = document.createElement("div");
    controls.className = "ledger-controls";
    const [chapterLabel, chapter] = choice("Chapter", "chapter", chapters);
    const [verdictLabel, verdict] = choice("Verdict", "verdict", verdicts);
    const searchLabel = document.createElement("label");
    searchLabel.className = "ledger-filter";
    searchLabel.textContent = "Text ";
    const search = document.createElement("input");
    search.type = "search";
    search.id = "ledger-filter-text";
    search.placeholder = "id, statement, function...";
    searchLabel.appendChild(search);
    const count = document.createElement("span");
    count.className = "ledger-count";
    count.id = "ledger-count";
    controls.append(chapterLabel, verdictLabel, searchLabel, count);
    const container = table.closest(".pst-scrollable-table-container") || table;
    container.parentNode.insertBefore(controls, container);

    function apply() {
      const words = search.value.trim().toLowerCase();
      let shown = 0;
      rows.forEach((row) => {
        const text = pair(row).map((part) => part.textContent).join(" ").toLowerCase();
        const visible =
          (!chapter.value || cellText(row, chapterAt) === chapter.value) &&
          (!verdict.value || cellText(row, verdictAt) === verdict.value) &&
          (!words || text.includes(words));
        pair(row).forEach((part) => { part.hidden = !visible; });
        shown += visible ? 1 : 0;
      });
      count.textContent = `${shown} of ${rows.length} rows`;
    }
    [chapter, verdict].forEach((select) => select.addEventListener("change", apply));
    search.addEventListener("input", apply);

    let sorted = { index: -1, ascending: true };
    [...table.tHead.rows[0].cells].forEach((cell, index) => {
      cell.classList.add("ledger-sortable");
      cell.title = "Sort by " + headings[index];
      cell.tabIndex = 0;
      const sort = () => {
        const ascending = sorted.index === index ? !sorted.ascending : true;
        sorted = { index, ascending };
        const keyed = [...body.rows].filter((row) => row.explanation).map((row, position) => {
          const text = cellText(row, index);
          return { row, text, number: asNumber(text), position };
        });
        const numeric = keyed.every((item) => !item.text || !isNaN(item.number));
        keyed.sort((a, b) => {
          const order = numeric
            ? (isNaN(a.number) ? Infinity : a.number) - (isNaN(b.number) ? Infinity : b.number)
            : a.text.localeCompare(b.text, undefined, { numeric: true });
          return (ascending ? order : -order) || a.position - b.position;
        });
        keyed.forEach((item) => body.append(...pair(item.row)));
        table.tHead.querySelectorAll("th").forEach((th) => th.removeAttribute("aria-sort"));
        cell.setAttribute("aria-sort", ascending ? "ascending" : "descending");
      };
      cell.addEventListener("click", sort);
      cell.addEventListener("keydown", (event) => {
        if (event.key === "Enter" || event.key === " ") {
          event.preventDefault();
          sort();
        }
      });
    });

    function showTarget() {
      rows.forEach((row) => pair(row).forEach((part) => part.classList.remove("ledger-target")));
      const id = decodeURIComponent(window.location.hash.slice(1));
      const target = id && document.getElementById(id);
      const row = target && target.closest("tr");
      if (!row || !rows.includes(row)) return;
      if (row.hidden) {
        chapter.value = verdict.value = search.value = "";
        apply();
      }
      pair(row).forEach((part) => part.classList.add("ledger-target"));
      row.scrollIntoView({ block: "center" });
    }
    window.addEventListener("hashchange", showTarget);
    window.addEventListener("load", showTarget);  // again once the browser has scrolled to it
    apply();
    showTarget();
  }

  document.addEventListener("DOMContentLoaded", () => {
    document.querySelectorAll("table.ledger-table").forEach(setUp);
  });
})();
