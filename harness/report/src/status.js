// Collects script errors from here on and, once the page has loaded,
// writes what the report's scripts achieved into #report-status as JSON:
// {"charts", "webgl", "replayViews", "replayMeshes", "replayLitPixels",
//  "hullTraceMeshes", "hullTraceLitPixels", "funnelCharts", "scalingCharts",
//  "tradeoffCharts", "scorecardCharts", "errors"}; scalingCharts counts the
// scaling charts drawn in the large-scenes section, tradeoffCharts its
// speed-against-accuracy charts, scorecardCharts the scorecard's
// pass-fraction chart.
window.talusReport = {webgl: false, replayViews: 0, replayMeshes: 0, replayLitPixels: [],
                      hullTraceMeshes: 0, hullTraceLitPixels: 0, funnelCharts: 0, errors: []};
window.addEventListener('error', e => { window.talusReport.errors.push(String(e.message)); });
window.addEventListener('load', () => {
  const s = window.talusReport;
  s.charts = typeof Chart === 'undefined' ? 0 : Object.keys(Chart.instances).length;
  s.scalingCharts = typeof Chart === 'undefined' ? 0 :
      Object.values(Chart.instances).filter(c => c.canvas.closest('#scenes-plots')).length;
  s.tradeoffCharts = typeof Chart === 'undefined' ? 0 :
      Object.values(Chart.instances).filter(c => c.canvas.closest('#scenes-tradeoff')).length;
  s.scorecardCharts = typeof Chart === 'undefined' ? 0 :
      Object.values(Chart.instances).filter(c => c.canvas.id === 'scorecard-chart').length;
  const node = document.getElementById('report-status');
  node.textContent = JSON.stringify(s);
  node.setAttribute('data-done', 'true');
});
