// Words for the simulated clock in the HUD: time since the start as h:mm:ss,
// a time-lapse rate as "×3 600", a temperature in °C.

/** `seconds` since the start as h:mm:ss (hours unbounded; the seconds rounded down). */
export function formatClock(seconds: number): string {
  const s = Number.isFinite(seconds) && seconds > 0 ? Math.floor(seconds) : 0;
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  const r = s % 60;
  return `${h}:${String(m).padStart(2, "0")}:${String(r).padStart(2, "0")}`;
}

/** A rate as "×3 600" (thousands apart by a thin space: a rate, not a quantity), "real time" for 1. */
export function formatRate(rate: number): string {
  if (rate === 1) return "real time";
  const whole = Math.round(rate);
  return `×${String(whole).replace(/\B(?=(\d{3})+(?!\d))/g, "\u2009")}`;
}

/** An achieved rate, rounded to two significant figures: the clock's pace jitters from frame to frame. */
export function formatAchievedRate(rate: number): string {
  if (!Number.isFinite(rate) || rate <= 0) return "×0";
  const digits = Math.max(0, Math.floor(Math.log10(rate)) - 1);
  const unit = 10 ** digits;
  return formatRate(Math.max(1, Math.round(rate / unit) * unit)).replace("real time", "×1");
}

/** °C with one decimal ("20.0 °C"). */
export function formatCelsius(celsius: number): string {
  return `${celsius.toFixed(1)} °C`;
}
