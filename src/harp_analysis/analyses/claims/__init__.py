"""The claims ledger's computations that belong to no analysis of their own, one module a chapter
(chapter1-chapter4, chapter6, chapter7, appendices), with the launch several share (launches)."""
