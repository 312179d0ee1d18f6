"""The derivation layer: from a System (the description) to what is derived from it.

Kinematics (transport theorem, constraint reduction), modes of the contacts (``mode``), sign regimes of
sliding friction (``regime``), the balance laws (``laws``), the joint solve of accelerations and
reactions (``solution``) and their evaluation at a state (``evaluation``).
"""
